#pragma once
#include <chrono>

namespace octrace {
/// Wall-clock stopwatch in milliseconds.
class Timer {
public:
    Timer() : start_(std::chrono::steady_clock::now()) {}
    double ms() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    }
    void reset() { start_ = std::chrono::steady_clock::now(); }

private:
    std::chrono::steady_clock::time_point start_;
};
/// Peak resident set size of this process in bytes (0 if unknown).
std::size_t peakRssBytes();
}  // namespace octrace
