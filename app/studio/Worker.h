#pragma once
// One background thread that runs jobs one at a time, newest first: posting a job asks the
// running one to stop (its cancel flag) and drops the ones still waiting, so that a window
// that keeps asking (a dragged slider, a moving camera) is answered with its latest wish only.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace octrace::studio {

class Worker {
public:
    using Job = std::function<void(const std::atomic<bool>& cancelled)>;
    Worker();
    ~Worker();  // cancels the running job and joins
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;

    /// Replaces what is waiting by `job`; with `cancelRunning`, asks the running job to stop.
    void post(Job job, bool cancelRunning = true);
    /// Asks the running job to stop and drops the waiting ones.
    void cancel();
    /// Whether a job is running or waiting.
    bool busy() const;

private:
    void loop();
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<Job> jobs_;
    std::shared_ptr<std::atomic<bool>> runningCancel_;
    bool running_ = false, quit_ = false;
    std::thread thread_;
};

}  // namespace octrace::studio
