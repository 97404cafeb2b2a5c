#include "octrace/util/Log.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>

namespace octrace::log {
namespace {
std::atomic<Level> gLevel{Level::Info};
std::mutex gMutex;
std::function<void(Level, const std::string&)> gSink;
std::function<std::string(const std::string&)> gWording;
thread_local Level tFloor = Level::Debug;
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
void setWording(std::function<std::string(const std::string&)> wording) {
    std::lock_guard<std::mutex> lock(gMutex);
    gWording = std::move(wording);
}
ThreadFloor::ThreadFloor(Level floor) : previous_(tFloor) { tFloor = std::max(tFloor, floor); }
ThreadFloor::~ThreadFloor() { tFloor = previous_; }
void message(Level l, const std::string& raw) {
    if (l < gLevel.load() || l < tFloor) return;
    std::lock_guard<std::mutex> lock(gMutex);
    const std::string text = gWording ? gWording(raw) : raw;
    if (gSink) {
        gSink(l, text);
        return;
    }
    std::fprintf(stderr, "octrace: %s%s\n", prefix(l), text.c_str());
}
}  // namespace octrace::log
