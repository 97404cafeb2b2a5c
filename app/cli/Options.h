#pragma once
// GNU-style long option parsing for the octrace CLI: "--name value" or "--name=value",
// flags without a value, positional arguments. Every option states its default in --help.
#include "octrace/model/OptionTable.h"
#include "octrace/model/Settings.h"
#include "octrace/util/Math.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace octrace::cli {

struct OptionSpec {
    std::string name;      // without the dashes; "o" is accepted as -o
    std::string argument;  // empty for a flag
    std::string help;      // one line; ends with the default
    std::function<void(const std::string&)> apply;
};

class OptionParser {
public:
    OptionParser(std::string command, std::string usage) : command_(std::move(command)), usage_(std::move(usage)) {}
    void add(OptionSpec spec) { specs_.push_back(std::move(spec)); }
    /// Parses args; returns the positional arguments. Throws UsageError.
    std::vector<std::string> parse(const std::vector<std::string>& args) const;
    /// The options the last parse() met, by name, in order (repeated ones once each).
    const std::vector<std::string>& given() const { return given_; }
    std::string help() const;
    const std::string& usage() const { return usage_; }
    const std::string& command() const { return command_; }

private:
    std::string command_, usage_;
    std::vector<OptionSpec> specs_;
    mutable std::vector<std::string> given_;
};

/// An option of the table (model/OptionTable.h): its flag, argument and help line come from there.
/// `detail` is what only the running program knows (model::Option::helpLine).
OptionSpec tableOption(const model::Option& o, std::function<void(const std::string&)> apply, const std::string& detail = "");
/// An option of the table whose value lands in the pipeline's specs at `targets`
/// (model::applySetting: the same parsing and checks as the sessions' and Python's).
OptionSpec settingOption(const model::Option& o, const model::SettingTargets& targets, const std::string& detail = "");
/// The table's checks of a numeric or choice option, for the apply function of tableOption;
/// they throw UsageError naming the option (`key`: the CLI says its flag).
inline double tableNumber(const model::Option& o, const std::string& text) { return model::parseNumber(o, text); }
inline int tableInt(const model::Option& o, const std::string& text) { return model::parseInteger(o, text); }
inline bool tableOnOff(const model::Option& o, const std::string& text) { return model::parseChoice(o, text) == "on"; }

/// Warns (log) for each option given in `p`'s last parse that `renderer` does not read, or
/// whose `needs` option is off (model::unusedWarning; isOn(key) says which Flag options are on).
void warnUnused(const OptionParser& p, const Renderer& renderer, const std::string& rendererName,
                const std::function<bool(std::string_view key)>& isOn = {});

}  // namespace octrace::cli
