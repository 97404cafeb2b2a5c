#include "LatencyMeter.h"

#include <algorithm>

namespace octrace::studio {

std::uint64_t LatencyMeter::input(Input kind, Clock::time_point at) {
    pending_.push_back({++serial_, kind, at});
    return serial_;
}

std::optional<double> LatencyMeter::painted(std::uint64_t serial, bool preview, Clock::time_point at) {
    std::optional<double> worst;
    while (!pending_.empty() && pending_.front().serial <= serial) {
        const Pending& p = pending_.front();
        const double ms = std::chrono::duration<double, std::milli>(at - p.at).count();
        samples_.push_back({p.kind, preview, ms});
        worst = std::max(worst.value_or(ms), ms);
        pending_.pop_front();
    }
    return worst;
}

void LatencyMeter::clear() {
    pending_.clear();
    samples_.clear();
}

}  // namespace octrace::studio
