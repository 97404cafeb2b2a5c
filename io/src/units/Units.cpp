#include "octrace/io/Units.h"

#include "input/InputFile.h"

#include "octrace/util/Error.h"

#include <udunits2.h>

#include <cctype>
#include <cstdlib>
#include <memory>
#include <mutex>

namespace octrace::io {
namespace {

/// The unit system, read once. UDUNITS-2's parser keeps global state, so every call into the
/// library holds `mutex`.
struct UnitSystem {
    std::mutex mutex;
    ut_system* system = nullptr;
    std::string failure;  ///< why the database could not be read (system null)

    UnitSystem() {
        ut_set_error_message_handler(ut_ignore);
        system = ut_read_xml(nullptr);
        if (!system) {
            const char* env = std::getenv("UDUNITS2_XML_PATH");
            failure = std::string("the UDUNITS-2 unit database could not be read (") +
                      (env ? std::string("UDUNITS2_XML_PATH=") + env : std::string("the library's default path")) +
                      ", status " + std::to_string(int(ut_get_status())) +
                      "): install Debian's libudunits2-data, or set UDUNITS2_XML_PATH to its udunits2.xml";
        }
    }
    // The system lives as long as the process: freeing it at exit would race late users.
};

UnitSystem& units() {
    static UnitSystem* s = new UnitSystem;  // thread-safe initialisation (C++11 magic statics)
    if (!s->system) throw Error(s->failure);
    return *s;
}

struct UnitDeleter {
    void operator()(ut_unit* u) const { ut_free(u); }
};
using UnitPtr = std::unique_ptr<ut_unit, UnitDeleter>;

/// Parses `text` (normalised); null when UDUNITS-2 does not know it. Caller holds the mutex.
UnitPtr parse(UnitSystem& s, const std::string& text) {
    if (text.empty()) return nullptr;
    return UnitPtr(ut_parse(s.system, text.c_str(), UT_UTF8));
}

std::string squeezed(const std::string& text) {  // lower case, without blanks and underscores
    std::string out;
    for (char c : text)
        if (c != ' ' && c != '_' && c != '\t') out += char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

}  // namespace

std::string normalizedUnits(const std::string& units) {
    const std::string t = detail::trim(units);
    std::string s = squeezed(t);
    // deg C, degree C, degrees Celsius, DEG C, deg_C, ...: the temperature, not an angle times it.
    for (const char* prefix : {"degrees", "degree", "deg"})
        if (s.rfind(prefix, 0) == 0) {
            const std::string rest = s.substr(std::char_traits<char>::length(prefix));
            if (rest == "c" || rest == "celsius" || rest == "centigrade") return "degC";
            if (rest == "k" || rest == "kelvin") return "K";
            if (rest == "f" || rest == "fahrenheit") return "degF";
            break;
        }
    return t;
}

bool knownUnits(const std::string& text) {
    UnitSystem& s = units();
    const std::string u = normalizedUnits(text);
    std::lock_guard lock(s.mutex);
    return parse(s, u) != nullptr;
}

std::optional<double> convertUnits(double value, const std::string& from, const std::string& to) {
    UnitSystem& s = units();
    const std::string f = normalizedUnits(from), t = normalizedUnits(to);
    std::lock_guard lock(s.mutex);
    const UnitPtr a = parse(s, f), b = parse(s, t);
    if (!a || !b || !ut_are_convertible(a.get(), b.get())) return std::nullopt;
    cv_converter* c = ut_get_converter(a.get(), b.get());
    if (!c) return std::nullopt;
    const double v = cv_convert_double(c, value);
    cv_free(c);
    return v;
}

double metresPer(const std::string& units) {
    // A plain number is dimensionless to UDUNITS-2 ("1", "10"): not a length.
    return convertUnits(1.0, units, "m").value_or(0.0);
}

double decibarsPer(const std::string& units) {
    if (squeezed(units) == "db") return 1.0;
    return convertUnits(1.0, units, "dbar").value_or(0.0);
}

}  // namespace octrace::io
