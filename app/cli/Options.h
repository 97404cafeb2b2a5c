#pragma once
// GNU-style long option parsing for the octrace CLI: "--name value" or "--name=value",
// flags without a value, positional arguments. Every option states its default in --help.
#include "octrace/model/OptionTable.h"
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
/// The table's checks of a numeric or choice option, for the apply function of tableOption;
/// they throw UsageError naming the option (`key`: the CLI says its flag).
inline double tableNumber(const model::Option& o, const std::string& text) { return model::parseNumber(o, text); }
inline int tableInt(const model::Option& o, const std::string& text) { return model::parseInteger(o, text); }
inline bool tableOnOff(const model::Option& o, const std::string& text) { return model::parseChoice(o, text) == "on"; }

/// Warns (log) for each option given in `p`'s last parse that `renderer` does not read, or
/// whose `needs` option is off (model::unusedWarning; isOn(key) says which Flag options are on).
void warnUnused(const OptionParser& p, const Renderer& renderer, const std::string& rendererName,
                const std::function<bool(std::string_view key)>& isOn = {});

// Strict value parsers; they throw UsageError naming the option and the text.
double parseNumber(const std::string& option, const std::string& text);
int parseInt(const std::string& option, const std::string& text, int lo, int hi);
dvec3 parseVec3(const std::string& option, const std::string& text);
/// "R,G,B" or "R,G,B,A", each in [0,1] (sRGB display values, as a user picks a colour).
vec4 parseColour(const std::string& option, const std::string& text, bool allowAlpha);
void parseSize(const std::string& option, const std::string& text, int& w, int& h);
/// A memory size: a positive number of bytes with an optional suffix K, M, G, T or KiB, MiB,
/// GiB, TiB (all powers of 1024, any case; "1.5G" is allowed), or N% of the physical memory.
std::uint64_t parseByteSize(const std::string& option, const std::string& text);

}  // namespace octrace::cli
