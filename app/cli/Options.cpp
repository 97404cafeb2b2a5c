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
#include <stdexcept>

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

OptionSpec settingOption(const model::Option& o, const model::SettingTargets& targets, const std::string& detail) {
    return tableOption(o, [&o, targets](const std::string& v) {
        if (!model::applySetting(o, v, targets))
            throw std::logic_error(std::string("option ") + o.key + " has no place in this command's specs");
    }, detail);
}

void warnUnused(const OptionParser& p, const Renderer& renderer, const std::string& rendererName,
                const std::function<bool(std::string_view key)>& isOn) {
    for (const std::string& name : p.given()) {
        const model::Option* o = model::findFlag(p.command(), name);
        if (!o) continue;
        if (auto w = model::unusedWarning(*o, renderer, rendererName, isOn)) log::warning(*w);
    }
}

}  // namespace octrace::cli
