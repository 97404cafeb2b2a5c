#pragma once
// A flat JSON object with keys in insertion order (stable output for tools and diffs).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace octrace::cli {

class StatsJson {
public:
    void set(const std::string& key, const std::string& value);
    void set(const std::string& key, const char* value) { set(key, std::string(value)); }
    void set(const std::string& key, double value);  // non-finite -> null
    void set(const std::string& key, std::uint64_t value);
    void set(const std::string& key, int value) { set(key, std::uint64_t(value < 0 ? 0 : value)); }
    void set(const std::string& key, bool value);
    std::string text() const;

private:
    void put(const std::string& key, std::string json);
    std::vector<std::pair<std::string, std::string>> items_;
};

}  // namespace octrace::cli
