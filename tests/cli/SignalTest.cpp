// Interrupting `octrace render` with SIGINT (Ctrl-C) or SIGTERM (kill) while it renders or
// while it writes its output: the process ends as the signal says (a shell reports 130 or
// 143), and leaves neither a partial output nor a temporary file behind.
#include "CliRunner.h"

#include <poll.h>
#include <signal.h>
#include <sys/inotify.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

using namespace octrace::testcli;

namespace {

std::string describeStatus(int status) {
    if (WIFEXITED(status)) return "exited with " + std::to_string(WEXITSTATUS(status));
    if (WIFSIGNALED(status)) return std::string("killed by ").append(strsignal(WTERMSIG(status)));
    return "status " + std::to_string(status);
}

std::string listing(const std::filesystem::path& dir) {
    std::string s;
    for (auto& e : std::filesystem::directory_iterator(dir)) s.append(" ").append(e.path().filename().string());
    return s.empty() ? " (empty)" : s;
}

// A render that takes minutes: every frame (4000x3000, 300 MB of Frame buffers) is drawn 1000 times.
std::vector<std::string> longRender(const std::string& out) {
    return {"render", "analytic:gyroid", "--iso", "0", "--depth", "9", "--size", "4000x3000", "--repeat", "1000", "--threads",
            "2", "-o", out};
}

}  // namespace

TEST(Signals, InterruptedWhileRenderingEndsBySignalAndLeavesNoOutput) {
    for (int sig : {SIGINT, SIGTERM}) {
        Scratch dir, logs;
        Child child(longRender(dir.path("out.png")), logs);
        // Rendering has begun once the frame's buffers (4000 x 3000 x 25 bytes) are resident.
        const auto start = std::chrono::steady_clock::now();
        while (child.residentBytes() < std::size_t(250) << 20 && std::chrono::steady_clock::now() - start < std::chrono::minutes(5))
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        ASSERT_GE(child.residentBytes(), std::size_t(250) << 20) << "the render did not start:\n" << slurp(logs.path("stderr"));
        ASSERT_EQ(::kill(child.pid(), sig), 0);
        const int status = child.wait();
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << strsignal(sig) << ": " << describeStatus(status);
        EXPECT_EQ(countEntries(dir.dir()), 0) << strsignal(sig) << " left:" << listing(dir.dir());
    }
}

// The output is written to a temporary name and renamed when complete. The writing takes tens
// of milliseconds, too short to catch reliably on a loaded machine, so the child is run with
// OCTRACE_TEST_STOP_WHILE_WRITING=1: it stops itself (SIGSTOP) right after creating its
// temporary (io/src/input/AtomicFile.cpp). Then it gets the signal and is continued. A run that still
// finished writing first (the hook not honoured) is tried again and fails the test in the end.
TEST(Signals, InterruptedWhileWritingRemovesItsTemporaryAndEndsBySignal) {
    for (int sig : {SIGINT, SIGTERM}) {
        bool caught = false;
        ::setenv("OCTRACE_TEST_STOP_WHILE_WRITING", "1", 1);  // inherited by the child
        for (int attempt = 0; attempt < 5 && !caught; ++attempt) {
            Scratch dir, logs;
            const int watch = ::inotify_init1(IN_CLOEXEC | IN_NONBLOCK);
            ASSERT_GE(watch, 0);
            ASSERT_GE(::inotify_add_watch(watch, dir.dir().c_str(), IN_CREATE), 0);
            Child child({"render", "analytic:gyroid", "--iso", "0", "--depth", "8", "--size", "4000x3000", "-o",
                         dir.path("out.exr")},
                        logs);
            // Wait for the temporary to be created (or for the child to end without one).
            std::string tmp;
            const auto start = std::chrono::steady_clock::now();
            while (tmp.empty() && std::chrono::steady_clock::now() - start < std::chrono::minutes(5)) {
                pollfd p{watch, POLLIN, 0};
                if (::poll(&p, 1, 100) <= 0) {
                    if (child.ended()) break;
                    continue;
                }
                alignas(inotify_event) char buf[4096];
                const ssize_t n = ::read(watch, buf, sizeof buf);
                for (ssize_t off = 0; off < n;) {
                    const auto* e = reinterpret_cast<const inotify_event*>(buf + off);
                    if (e->len > 0 && std::strstr(e->name, ".tmp-")) tmp = e->name;
                    off += ssize_t(sizeof(inotify_event) + e->len);
                }
            }
            ::close(watch);
            ASSERT_FALSE(tmp.empty()) << "no temporary appeared:\n" << slurp(logs.path("stderr"));
            // Wait for its own stop. No SIGSTOP of ours: sent between the temporary's creation
            // and the child's raise, it would be consumed first, and the child's own stop would
            // come after our signal and SIGCONT, leaving it stopped for good.
            int status = child.wait(true);
            if (!WIFSTOPPED(status) || !std::filesystem::exists(dir.path(tmp))) {
                // Finished writing first: the output is then complete and the temporary gone.
                if (!WIFSTOPPED(status)) {
                    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << describeStatus(status);
                } else {
                    ::kill(child.pid(), SIGCONT);
                    child.wait();
                }
                EXPECT_FALSE(std::filesystem::exists(dir.path(tmp)));
                continue;
            }
            caught = true;
            ASSERT_EQ(::kill(child.pid(), sig), 0);
            ASSERT_EQ(::kill(child.pid(), SIGCONT), 0);
            status = child.wait();
            EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << strsignal(sig) << ": " << describeStatus(status);
            EXPECT_EQ(countEntries(dir.dir()), 0) << strsignal(sig) << " left:" << listing(dir.dir());
        }
        ::unsetenv("OCTRACE_TEST_STOP_WHILE_WRITING");
        EXPECT_TRUE(caught) << strsignal(sig) << ": in 5 runs, the writing was never caught in progress";
    }
}

// The clean-up does not take over signals the caller ignores: `nohup octrace ...` keeps
// running through a hang-up.
TEST(Signals, AnIgnoredSignalStaysIgnored) {
    Scratch dir, logs;
    struct sigaction ignore {}, old{};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ASSERT_EQ(::sigaction(SIGHUP, &ignore, &old), 0);  // inherited across fork and exec
    Child child({"render", "analytic:sphere:33", "--iso", "0", "--depth", "6", "--size", "800x600", "--repeat", "20", "-o",
                 dir.path("out.png")},
                logs);
    ::sigaction(SIGHUP, &old, nullptr);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    ::kill(child.pid(), SIGHUP);
    const int status = child.wait();
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << describeStatus(status) << "\n" << slurp(logs.path("stderr"));
    EXPECT_TRUE(std::filesystem::exists(dir.path("out.png")));
}
