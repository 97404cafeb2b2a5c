#include "octrace/util/Log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace octrace::log {
namespace {
std::atomic<Level> gLevel{Level::Info};
std::mutex gMutex;
std::function<void(Level, const std::string&)> gSink;
const char* prefix(Level l) {
    switch (l) {
    case Level::Debug: return "debug: ";
    case Level::Info: return "";
    case Level::Warning: return "warning: ";
    case Level::Error: return "error: ";
    default: return "";
    }
}
}  // namespace

void setLevel(Level level) { gLevel = level; }
Level level() { return gLevel; }
void setSink(std::function<void(Level, const std::string&)> sink) {
    std::lock_guard<std::mutex> lock(gMutex);
    gSink = std::move(sink);
}
void message(Level l, const std::string& text) {
    if (l < gLevel.load()) return;
    std::lock_guard<std::mutex> lock(gMutex);
    if (gSink) {
        gSink(l, text);
        return;
    }
    std::fprintf(stderr, "octrace: %s%s\n", prefix(l), text.c_str());
}
}  // namespace octrace::log
