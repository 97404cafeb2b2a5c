#pragma once
/// @file Parameter.h
/// How core and io messages name a setting. A library does not know which front end called
/// it (the CLI has flags, the studio controls, Python keywords), so an error or log text names a
/// parameter by its key in backticks, e.g. "try a smaller `depth` or a larger `max_memory`".
/// The keys are those of the options table (app/model); each front end rewrites them into its
/// own words with sayParameters() before showing the text, and a text shown as it is still
/// reads well.
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace octrace {

/// `text` between two `mark`s. Appended rather than "'" + std::string(text) + "'", which draws
/// a false -Wrestrict from GCC 12 (an overlap inside operator+(const char*, string&&)).
inline std::string enclosed(std::string_view text, char mark) {
    std::string s;
    s.reserve(text.size() + 2);
    s += mark;
    s += text;
    s += mark;
    return s;
}

/// `key` as a message names it: "`key`".
inline std::string param(std::string_view key) { return enclosed(key, '`'); }

/// `text` with every "`key`" for which `say` returns a word replaced by that word; other
/// backticked words (and an unmatched backtick) are kept as they are.
std::string sayParameters(std::string_view text, const std::function<std::optional<std::string>(std::string_view key)>& say);

}  // namespace octrace
