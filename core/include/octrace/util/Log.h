#pragma once
/// @file Log.h
/// One logging facade. The library never prints to stdout; messages go to a sink
/// (stderr by default) filtered by level. Thread-safe.
#include <functional>
#include <string>

namespace octrace::log {

enum class Level { Debug = 0, Info = 1, Warning = 2, Error = 3, Quiet = 4 };

/// Messages below this level are dropped. Default: Info.
void setLevel(Level level);
Level level();

/// Replace the sink (e.g. the Qt application shows messages in a panel). Pass {} for stderr.
void setSink(std::function<void(Level, const std::string&)> sink);

/// Rewrite every message before it reaches the sink: a front end names the parameters of core
/// and io messages (util/Parameter.h) in its own words. Pass {} to show them as they are.
void setWording(std::function<std::string(const std::string&)> wording);

/// While one lives, this thread's messages below `floor` are dropped too (other threads' are
/// not): to redo work whose messages were already given, e.g. a second read of one file.
class ThreadFloor {
public:
    explicit ThreadFloor(Level floor);
    ~ThreadFloor();
    ThreadFloor(const ThreadFloor&) = delete;
    ThreadFloor& operator=(const ThreadFloor&) = delete;

private:
    Level previous_;
};

void message(Level level, const std::string& text);
inline void debug(const std::string& t) { message(Level::Debug, t); }
inline void info(const std::string& t) { message(Level::Info, t); }
inline void warning(const std::string& t) { message(Level::Warning, t); }
inline void error(const std::string& t) { message(Level::Error, t); }

}  // namespace octrace::log
