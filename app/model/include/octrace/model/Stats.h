#pragma once
/// @file Stats.h
/// A frame's or a build's figures as an ordered list of named values: what `--stats` writes as
/// a flat JSON object (keys in insertion order, stable for tools and diffs) and what Python
/// returns as a dict. Text values may name settings by key (util/Parameter.h); json() says
/// them in the front end's words.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace octrace::model {

class Stats {
public:
    /// null (a figure that does not apply, e.g. us_per_ray of a direct renderer), true/false,
    /// a count, a number, a text.
    using Value = std::variant<std::nullptr_t, bool, std::uint64_t, double, std::string>;

    void set(const std::string& key, const std::string& value) { put(key, value); }
    void set(const std::string& key, const char* value) { put(key, std::string(value)); }
    void set(const std::string& key, double value);  ///< non-finite: null
    void set(const std::string& key, std::uint64_t value) { put(key, value); }
    void set(const std::string& key, int value) { put(key, std::uint64_t(value < 0 ? 0 : value)); }
    void set(const std::string& key, bool value) { put(key, value); }

    const std::vector<std::pair<std::string, Value>>& entries() const { return items_; }
    /// The value of `key`, or nullptr when there is none.
    const Value* find(std::string_view key) const;

    /// The JSON object, one member per line; `say` rewords text values (e.g. model::sayForCli).
    std::string json(const std::function<std::string(std::string_view)>& say = {}) const;

private:
    void put(const std::string& key, Value v);  // a key set again keeps its place
    std::vector<std::pair<std::string, Value>> items_;
};

}  // namespace octrace::model
