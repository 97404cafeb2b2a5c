#include "octrace/model/Stats.h"

#include <cmath>
#include <cstdio>

namespace octrace::model {
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

void Stats::put(const std::string& key, Value v) {
    for (auto& kv : items_)
        if (kv.first == key) {
            kv.second = std::move(v);
            return;
        }
    items_.emplace_back(key, std::move(v));
}

void Stats::set(const std::string& key, double value) {
    if (std::isfinite(value)) put(key, value);
    else put(key, nullptr);
}

const Stats::Value* Stats::find(std::string_view key) const {
    for (const auto& kv : items_)
        if (kv.first == key) return &kv.second;
    return nullptr;
}

std::string Stats::json(const std::function<std::string(std::string_view)>& say) const {
    std::string s = "{\n";
    for (std::size_t i = 0; i < items_.size(); ++i) {
        std::string value;
        const Value& v = items_[i].second;
        if (std::holds_alternative<std::nullptr_t>(v)) {
            value = "null";
        } else if (const bool* b = std::get_if<bool>(&v)) {
            value = *b ? "true" : "false";
        } else if (const std::uint64_t* n = std::get_if<std::uint64_t>(&v)) {
            value = std::to_string(*n);
        } else if (const double* d = std::get_if<double>(&v)) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.10g", *d);
            value = buf;
        } else {
            const std::string& text = std::get<std::string>(v);
            value = quote(say ? say(text) : text);
        }
        s += "  " + quote(items_[i].first) + ": " + value + (i + 1 < items_.size() ? ",\n" : "\n");
    }
    return s + "}\n";
}

}  // namespace octrace::model
