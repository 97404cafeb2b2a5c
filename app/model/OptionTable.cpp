#include "octrace/model/OptionTable.h"

#include "octrace/io/Units.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parameter.h"

#include <array>
#include <cctype>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <sstream>

namespace octrace::model {
namespace {

constexpr std::array kOptions{
    &opt::depth,           &opt::iso,         &opt::variable,         &opt::time,        &opt::series,      &opt::volume,
    &opt::form,            &opt::surface, &opt::inside,      &opt::threads,          &opt::maxMemory,   &opt::verticalScale,
    &opt::terrainDepth,    &opt::crs,         &opt::heightAttr,       &opt::baseAttr,    &opt::dem,         &opt::texture,
    &opt::cut,             &opt::renderer,    &opt::fov,              &opt::orthoHeight, &opt::projection,
    &opt::lod,             &opt::level,       &opt::colourCoherence,  &opt::colourFillBackground,
    &opt::colourTolerance, &opt::branchUp,    &opt::tileSize, &opt::missCoherence,    &opt::repeat,      &opt::width,
    &opt::height,          &opt::octree,      &opt::leafObjects,      &opt::samples,     &opt::bounces,
    &opt::ambient,         &opt::lighting,    &opt::shadows,          &opt::bakeAo,      &opt::bakeAoDistance,
    &opt::bakeShadows,     &opt::dpi, &opt::bakeLight, &opt::colourRange, &opt::maskedColour, &opt::floorColour, &opt::background, &opt::light, &opt::cameraPos, &opt::lookAt, &opt::up, &opt::verify, &opt::baseline, &opt::figure, &opt::title, &opt::caption, &opt::printSize, &opt::scaleBar, &opt::coastline,         &opt::plane, &opt::at, &opt::format, &opt::ascii, &opt::index,            &opt::compression, &opt::sampleCount,
    &opt::seed,            &opt::clip,        &opt::extendDown,       &opt::region,      &opt::depthRange,     &opt::mapProjection,
    &opt::lodSelect,       &opt::bake,        &opt::colour,           &opt::colormap,    &opt::window,
    &opt::colourBy,        &opt::floor,       &opt::size,        &opt::times,       &opt::fps,
    &opt::orbit,           &opt::frames,
};

std::string numberText(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

std::string withUnit(std::string text, const Option& o) {
    if (*o.unit) text += std::string(" ") + o.unit;
    return text;
}

[[noreturn]] void refuse(const Option& o, const std::string& what) { throw UsageError(param(o.key) + ": " + what); }

std::vector<std::string> split(std::string_view text, char sep) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(sep, start);
        parts.emplace_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    return parts;
}

std::string spaced(std::string_view key) {
    std::string s(key);
    for (char& c : s)
        if (c == '_') c = ' ';
    return s;
}

}  // namespace

std::vector<std::string> Option::choiceList() const { return *choices ? split(choices, '|') : std::vector<std::string>{}; }

std::string Option::defaultChoice() const {
    const auto words = choiceList();
    const std::size_t i = std::size_t(defaultValue);
    return i < words.size() ? words[i] : std::string();
}

bool Option::inRange(double v) const {
    if (!std::isfinite(v)) return false;
    if (minOpen ? !(v > min) : !(v >= min)) return false;
    if (maxOpen ? !(v < max) : !(v <= max)) return false;
    return true;
}

std::string Option::rangeText() const {
    const bool lo = std::isfinite(min), hi = std::isfinite(max);
    if (lo && hi)
        return withUnit(std::string(minOpen ? "(" : "[") + numberText(min) + ", " + numberText(max) + (maxOpen ? ")" : "]"), *this);
    if (lo) return withUnit(std::string(minOpen ? "> " : ">= ") + numberText(min), *this);
    if (hi) return withUnit(std::string(maxOpen ? "< " : "<= ") + numberText(max), *this);
    return withUnit("any number", *this);
}

std::string Option::defaultSaid() const {
    if (*defaultText) return defaultText;
    switch (kind) {
    case OptionKind::Flag: return "off";
    case OptionKind::Integer:
    case OptionKind::Number: return numberText(defaultValue);
    case OptionKind::Choice: return defaultChoice();
    case OptionKind::Text: return *unit ? numberText(defaultValue) + unit : "none";
    }
    return {};
}

std::string Option::helpLine(const std::string& detail) const {
    std::string line = help;
    if (!detail.empty()) line += "; " + detail;
    if (kind == OptionKind::Integer || kind == OptionKind::Number) line += ", " + rangeText();
    if (renderers) line += "; renderers " + voxelRenderersThat(renderers);
    if (*needs) line += ", with " + param(needs);
    return line + " (default " + defaultSaid() + ")";
}

std::string Option::docLine() const {
    std::string line = "*Options table: default " + sayForCli(defaultSaid());
    if (kind == OptionKind::Integer || kind == OptionKind::Number) line += "; " + rangeText();
    if (kind == OptionKind::Choice) line += "; one of " + std::string(choices);
    if (renderers) line += "; read by " + (*renderersSaid ? sayForCli(renderersSaid) : voxelRenderersThat(renderers));
    if (*needs) line += " with " + sayForCli(param(needs));
    if (*session) line += "; session member `" + std::string(session) + "`";
    if (*label) line += "; studio control \"" + std::string(label) + "\"";
    std::string also;
    for (const std::string& c : split(commands, ' '))
        if (c != docCommand()) also += (also.empty() ? "" : ", ") + c;
    if (!also.empty()) line += "; also " + also;
    return line + ".*";
}

std::string Option::docCommand() const {
    if (takenBy("render")) return "render";
    const auto all = split(commands, ' ');
    return all.empty() ? std::string() : all.front();
}

bool Option::takenBy(std::string_view command) const {
    for (const std::string& c : split(commands, ' '))
        if (c == command) return true;
    return false;
}

std::span<const Option* const> allOptions() { return kOptions; }

const Option* findOption(std::string_view key) {
    for (const Option* o : kOptions)
        if (key == o->key) return o;
    return nullptr;
}

const Option* findFlag(std::string_view command, std::string_view flag) {
    for (const Option* o : kOptions)
        if (flag == o->flag && o->takenBy(command)) return o;
    return nullptr;
}

std::optional<std::string> valueProblem(const Option& o, double value) {
    if (o.kind == OptionKind::Integer && std::isfinite(value) && value != std::floor(value))
        return numberText(value) + " is not a whole number";
    if (!o.inRange(value)) return numberText(value) + " is outside " + o.rangeText();
    return std::nullopt;
}

std::string sessionMember(const Option& o) {
    const std::string_view s = o.session;
    const std::size_t dot = s.rfind('.');
    return std::string(dot == std::string_view::npos ? s : s.substr(dot + 1));
}

double checkNumber(const Option& o, double value) {
    if (auto problem = valueProblem(o, value)) refuse(o, *problem);
    return value;
}

int checkInteger(const Option& o, double value) { return int(checkNumber(o, value)); }

double parseFinite(const Option& o, const std::string& text) {
    const char* b = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(b, &end);
    if (text.empty() || end != b + text.size() || errno == ERANGE || !std::isfinite(v))
        refuse(o, "'" + text + "' is not a finite number");
    return v;
}

double parseNumber(const Option& o, const std::string& text) { return checkNumber(o, parseFinite(o, text)); }

Quantity parseQuantity(const Option& o, const std::string& text) {
    const char* b = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(b, &end);
    if (text.empty() || end == b || errno == ERANGE || !std::isfinite(v) || std::isspace(static_cast<unsigned char>(*b)))
        refuse(o, "'" + text + "' is not a number with an optional unit (e.g. 10, 10degC, 283.15K)");
    Quantity q{v, std::string(end), text};
    const std::size_t first = q.unit.find_first_not_of(" \t"), last = q.unit.find_last_not_of(" \t");
    q.unit = first == std::string::npos ? std::string() : q.unit.substr(first, last - first + 1);
    if (q.unit.empty()) {
        q.value = checkNumber(o, v);
    } else if (!io::knownUnits(q.unit)) {
        refuse(o, "unknown unit '" + q.unit + "' in '" + text +
                      "' (UDUNITS-2 does not know it: write a unit such as degC, K, m, km or dbar after the number, or "
                      "give a plain number in the units of the field)");
    }
    return q;
}

double quantityIn(const Quantity& q, const std::string& units, const std::string& what, const std::string& subject) {
    if (q.unit.empty()) return q.value;
    const std::string given = what + " " + q.text;
    if (units.find_first_not_of(" \t") == std::string::npos)
        throw InputError(subject + " has no units, so " + given + " cannot be converted into them (give a plain number, in "
                                   "the variable's own values)");
    if (!io::knownUnits(units))
        throw InputError(subject + " is in '" + units + "', which UDUNITS-2 does not know, so " + given +
                         " cannot be converted into it (give a plain number in " + units + ")");
    const auto v = io::convertUnits(q.value, q.unit, units);
    if (!v || !std::isfinite(*v))
        throw InputError(subject + " is in " + units + ": " + given + " does not convert to " + units +
                         " (give a value in a unit of the same quantity as " + units + ", or a plain number in " + units + ")");
    return *v;
}

int parseInteger(const Option& o, const std::string& text) {
    const char* b = text.c_str();
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(b, &end, 10);
    if (text.empty() || end != b + text.size() || errno == ERANGE) refuse(o, "'" + text + "' is not an integer");
    return checkInteger(o, double(v));
}

std::string parseChoice(const Option& o, const std::string& text) {
    const auto words = o.choiceList();
    for (const auto& w : words)
        if (w == text) return w;
    std::string said;
    for (std::size_t i = 0; i < words.size(); ++i) said += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
    refuse(o, "choose " + said + ", got '" + text + "'");
}

std::optional<std::string> unusedWarning(const Option& o, const Renderer& renderer, const std::string& rendererName,
                                         const std::function<bool(std::string_view key)>& isOn) {
    if (o.renderers && !(renderer.*o.renderers)())
        return param(o.key) + " has no effect on renderer " + rendererName + (*o.renderersSaid ? std::string(" (only on ") + o.renderersSaid + ")" : "");
    if (*o.needs && !(isOn && isOn(o.needs))) return param(o.key) + " has no effect without " + param(o.needs);
    return std::nullopt;
}

std::string sayForCli(std::string_view text) {
    return sayParameters(text, [](std::string_view key) -> std::optional<std::string> {
        const Option* o = findOption(key);
        if (o && *o->flag) return "--" + std::string(o->flag);
        if (key == opt::width.key || key == opt::height.key) return "--" + std::string(opt::size.flag);
        return spaced(key);
    });
}

std::string sayForSession(std::string_view text) {
    return sayParameters(text, [](std::string_view key) -> std::optional<std::string> {
        const Option* o = findOption(key);
        if (o && *o->session) return std::string(o->session);
        return spaced(key);
    });
}

std::string sayForStudio(std::string_view text) {
    return sayParameters(text, [](std::string_view key) -> std::optional<std::string> {
        const Option* o = findOption(key);
        if (o && *o->label) return enclosed(o->label, '\'');
        return spaced(key);
    });
}

std::string sayForPython(std::string_view text) {
    return sayParameters(text, [](std::string_view key) -> std::optional<std::string> {
        if (key == opt::width.key || key == opt::height.key) return enclosed(opt::size.key, '\'');
        if (findOption(key)) return enclosed(key, '\'');
        return spaced(key);
    });
}

}  // namespace octrace::model
