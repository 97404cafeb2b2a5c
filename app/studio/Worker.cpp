#include "Worker.h"

namespace octrace::studio {

Worker::Worker() : thread_([this] { loop(); }) {}

Worker::~Worker() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
        jobs_.clear();
        if (runningCancel_) *runningCancel_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void Worker::post(Job job, bool cancelRunning) {
    {
        std::lock_guard lock(mutex_);
        jobs_.clear();
        jobs_.push_back(std::move(job));
        if (cancelRunning && runningCancel_) *runningCancel_ = true;
    }
    wake_.notify_all();
}

void Worker::cancel() {
    std::lock_guard lock(mutex_);
    jobs_.clear();
    if (runningCancel_) *runningCancel_ = true;
}

bool Worker::busy() const {
    std::lock_guard lock(mutex_);
    return running_ || !jobs_.empty();
}

void Worker::loop() {
    for (;;) {
        Job job;
        std::shared_ptr<std::atomic<bool>> flag;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return quit_ || !jobs_.empty(); });
            if (quit_) return;
            job = std::move(jobs_.front());
            jobs_.pop_front();
            flag = std::make_shared<std::atomic<bool>>(false);
            runningCancel_ = flag;
            running_ = true;
        }
        job(*flag);
        std::lock_guard lock(mutex_);
        runningCancel_.reset();
        running_ = false;
    }
}

}  // namespace octrace::studio
