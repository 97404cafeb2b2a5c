#include "StatsJson.h"

#include "octrace/model/OptionTable.h"

#include <cmath>
#include <cstdio>

namespace octrace::cli {
namespace {
std::string quote(const std::string& s) {
    std::string o = "\"";
    for (char c : s) {
        switch (c) {
        case '"': o += "\\\""; break;
        case '\\': o += "\\\\"; break;
        case '\n': o += "\\n"; break;
        case '\t': o += "\\t"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "\\u%04x", c);
                o += buf;
            } else {
                o += c;
            }
        }
    }
    return o + "\"";
}
}  // namespace

void StatsJson::put(const std::string& key, std::string json) {
    for (auto& kv : items_)
        if (kv.first == key) {
            kv.second = std::move(json);
            return;
        }
    items_.emplace_back(key, std::move(json));
}
// Texts of core, io and the pipeline name settings by key (util/Parameter.h): said as flags here.
void StatsJson::set(const std::string& key, const std::string& value) { put(key, quote(model::sayForCli(value))); }
void StatsJson::set(const std::string& key, double value) {
    if (!std::isfinite(value)) {
        put(key, "null");
        return;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10g", value);
    put(key, buf);
}
void StatsJson::set(const std::string& key, std::uint64_t value) { put(key, std::to_string(value)); }
void StatsJson::set(const std::string& key, bool value) { put(key, value ? "true" : "false"); }

std::string StatsJson::text() const {
    std::string s = "{\n";
    for (std::size_t i = 0; i < items_.size(); ++i)
        s += "  " + quote(items_[i].first) + ": " + items_[i].second + (i + 1 < items_.size() ? ",\n" : "\n");
    return s + "}\n";
}

}  // namespace octrace::cli
