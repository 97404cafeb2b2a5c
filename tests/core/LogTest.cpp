// The logging facade's thread floor (util/Log.h): a second pass over work whose messages were
// already given says nothing on its thread, and nothing else is silenced.
#include "octrace/util/Log.h"

#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <thread>
#include <vector>

using namespace octrace;

namespace {
struct Collected {
    std::mutex mutex;
    std::vector<std::string> lines;
};
}  // namespace

TEST(Log, AThreadFloorDropsThisThreadsMessagesBelowItOnlyWhileItLives) {
    Collected got;
    log::setSink([&](log::Level, const std::string& text) {
        std::lock_guard<std::mutex> lock(got.mutex);
        got.lines.push_back(text);
    });
    log::info("before");
    {
        const log::ThreadFloor quiet(log::Level::Error);
        log::info("info under the floor");
        log::warning("warning under the floor");
        log::error("error under the floor");
        std::thread other([] { log::warning("another thread's warning"); });
        other.join();
        {
            // A lower floor inside does not lower it.
            const log::ThreadFloor inner(log::Level::Info);
            log::warning("inner warning");
        }
        log::warning("after the inner floor");
    }
    log::info("after");
    log::setSink({});
    const std::vector<std::string> want = {"before", "error under the floor", "another thread's warning", "after"};
    EXPECT_EQ(got.lines, want);
}
