#include "Options.h"

#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace octrace::cli {

std::vector<std::string> OptionParser::parse(const std::vector<std::string>& args) const {
    std::vector<std::string> positional;
    given_.clear();
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--") {
            positional.insert(positional.end(), args.begin() + std::ptrdiff_t(i) + 1, args.end());
            break;
        }
        std::string name, value;
        bool hasValue = false;
        if (a.rfind("--", 0) == 0) {
            name = a.substr(2);
            auto eq = name.find('=');
            if (eq != std::string::npos) {
                value = name.substr(eq + 1);
                name = name.substr(0, eq);
                hasValue = true;
            }
        } else if (a.size() == 2 && a[0] == '-' && a[1] != '-') {
            name = a.substr(1);
        } else {
            positional.push_back(a);
            continue;
        }
        const OptionSpec* spec = nullptr;
        for (const auto& s : specs_)
            if (s.name == name) spec = &s;
        if (!spec) throw UsageError("unknown option '" + a + "' for '" + command_ + "'");
        if (std::find(given_.begin(), given_.end(), name) == given_.end()) given_.push_back(name);
        if (spec->argument.empty()) {
            if (hasValue) throw UsageError("option --" + name + " takes no value");
            spec->apply("");
            continue;
        }
        if (!hasValue) {
            if (i + 1 >= args.size()) throw UsageError("option --" + name + " needs a value (" + spec->argument + ")");
            value = args[++i];
        }
        spec->apply(value);
    }
    return positional;
}

std::string OptionParser::help() const {
    std::ostringstream s;
    s << "usage: " << usage_ << "\n\noptions:\n";
    for (const auto& o : specs_) {
        std::string left = (o.name.size() == 1 ? "-" : "--") + o.name + (o.argument.empty() ? "" : " " + o.argument);
        s << "  " << left;
        if (left.size() < 28) s << std::string(28 - left.size(), ' ');
        else s << "\n" << std::string(30, ' ');
        s << o.help << "\n";
    }
    return s.str();
}

OptionSpec tableOption(const model::Option& o, std::function<void(const std::string&)> apply, const std::string& detail) {
    return {o.flag, o.kind == model::OptionKind::Flag ? "" : o.argument, model::sayForCli(o.helpLine(detail)), std::move(apply)};
}

void warnUnused(const OptionParser& p, const Renderer& renderer, const std::string& rendererName,
                const std::function<bool(std::string_view key)>& isOn) {
    for (const std::string& name : p.given()) {
        const model::Option* o = model::findFlag(p.command(), name);
        if (!o) continue;
        if (auto w = model::unusedWarning(*o, renderer, rendererName, isOn)) log::warning(*w);
    }
}

double parseNumber(const std::string& option, const std::string& text) {
    const char* b = text.c_str();
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(b, &end);
    if (text.empty() || end != b + text.size() || errno == ERANGE || !std::isfinite(v))
        throw UsageError("--" + option + ": '" + text + "' is not a finite number");
    return v;
}

int parseInt(const std::string& option, const std::string& text, int lo, int hi) {
    const char* b = text.c_str();
    char* end = nullptr;
    errno = 0;
    long v = std::strtol(b, &end, 10);
    if (text.empty() || end != b + text.size() || errno == ERANGE)
        throw UsageError("--" + option + ": '" + text + "' is not an integer");
    if (v < lo || v > hi) {
        std::ostringstream s;
        s << "--" << option << ": " << v << " is out of range [" << lo << ", " << hi << "]";
        throw UsageError(s.str());
    }
    return int(v);
}

namespace {
std::vector<std::string> split(const std::string& text, char sep) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : text) {
        if (c == sep) {
            parts.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    parts.push_back(cur);
    return parts;
}
}  // namespace

dvec3 parseVec3(const std::string& option, const std::string& text) {
    auto p = split(text, ',');
    if (p.size() != 3) throw UsageError("--" + option + ": expected X,Y,Z, got '" + text + "'");
    return dvec3(parseNumber(option, p[0]), parseNumber(option, p[1]), parseNumber(option, p[2]));
}

vec4 parseColour(const std::string& option, const std::string& text, bool allowAlpha) {
    auto p = split(text, ',');
    if (p.size() != 3 && !(allowAlpha && p.size() == 4))
        throw UsageError("--" + option + ": expected R,G,B" + std::string(allowAlpha ? "[,A]" : "") + " in [0,1], got '" +
                         text + "'");
    vec4 c(1.0f);
    for (std::size_t i = 0; i < p.size(); ++i) {
        double v = parseNumber(option, p[i]);
        if (v < 0.0 || v > 1.0) throw UsageError("--" + option + ": component '" + p[i] + "' is outside [0,1]");
        c[int(i)] = float(v);
    }
    return c;
}

void parseSize(const std::string& option, const std::string& text, int& w, int& h) {
    auto x = text.find('x');
    if (x == std::string::npos) throw UsageError("--" + option + ": expected WxH (e.g. 1600x1200), got '" + text + "'");
    (void)option;
    w = model::parseInteger(model::opt::width, text.substr(0, x));
    h = model::parseInteger(model::opt::height, text.substr(x + 1));
}

std::uint64_t parseByteSize(const std::string& option, const std::string& text) {
    const char* b = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(b, &end);
    std::string suffix(end);
    for (char& c : suffix) c = char(std::tolower(static_cast<unsigned char>(c)));
    const auto bad = [&](const std::string& why) {
        throw UsageError("--" + option + ": '" + text + "' " + why +
                         " (expected bytes with an optional K, M, G, T or KiB, MiB, GiB, TiB, e.g. 8G, or N% of the memory)");
    };
    if (text.empty() || end == b || errno == ERANGE || !std::isfinite(v) || std::isspace(static_cast<unsigned char>(*b)))
        bad("is not a memory size");
    if (!(v > 0.0)) bad("must be positive");
    double bytes = v;
    if (suffix == "%") {
        if (v > 100.0) bad("is more than 100%");
        const std::uint64_t physical = physicalMemoryBytes();
        if (physical == 0) bad("is a share of the physical memory, which cannot be read here");
        bytes = v / 100.0 * double(physical);
    } else {
        const char* units[] = {"", "k", "m", "g", "t"};
        int power = -1;
        for (int i = 0; i < 5; ++i)
            if (suffix == units[i] || (i > 0 && suffix == std::string(units[i]) + "ib")) power = i;
        if (power < 0) bad("has an unknown unit '" + std::string(end) + "'");
        bytes = std::ldexp(v, 10 * power);
    }
    if (bytes < 1.0) bad("is less than one byte");
    if (bytes >= 1.8e19) bad("is too large");
    return std::uint64_t(bytes);
}

}  // namespace octrace::cli
