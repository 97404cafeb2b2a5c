#pragma once
// Input-to-paint latency of camera moves, as the studio measures it itself (issue 23: "orbiting
// CT bone at depth 9 in a 1280x800 view, the time from the mouse event to the painted frame").
//
// Each input event that moves the camera (or ends a move: the exact frame follows) is stamped
// when the window handles it and gets a serial; a frame request carries the serial of the latest
// input it shows. When the main view has painted a frame, every input up to that frame's serial
// not answered before is answered: its latency is the paint time minus its stamp. An input whose
// frame was dropped (the Worker keeps the newest request only, a moving camera cancels the frame
// being rendered) waits for a later frame, and its latency says so.
//
// The stamp is taken when the GUI thread handles the event, not when the window system made it:
// time the event spent queued behind other GUI work is not counted. GUI thread only.
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

namespace octrace::studio {

class LatencyMeter {
public:
    using Clock = std::chrono::steady_clock;
    enum class Input { Move, Finish };  ///< a camera move; the end of one (button released, key, wheel step)
    struct Sample {
        Input input;
        bool preview;  ///< the frame that answered it was a coarse preview
        double ms;     ///< from the input's stamp to the end of the paint
    };

    /// An input event handled now; returns its serial (the latest, until the next input).
    std::uint64_t input(Input kind, Clock::time_point at = Clock::now());
    /// The serial of the latest input (0: none yet).
    std::uint64_t latest() const { return serial_; }
    /// The main view finished painting, at `at`, a frame showing the inputs up to `serial`.
    /// Returns the largest latency answered (ms), or nothing when it answered no new input.
    std::optional<double> painted(std::uint64_t serial, bool preview, Clock::time_point at = Clock::now());
    /// Every latency measured since the last clear().
    const std::vector<Sample>& samples() const { return samples_; }
    /// Inputs still waiting for a painted frame.
    std::size_t unanswered() const { return pending_.size(); }
    void clear();

private:
    struct Pending {
        std::uint64_t serial;
        Input kind;
        Clock::time_point at;
    };
    std::uint64_t serial_ = 0;
    std::deque<Pending> pending_;
    std::vector<Sample> samples_;
};

}  // namespace octrace::studio
