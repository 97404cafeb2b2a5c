#include "input/ChildProbe.h"

#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <thread>

#include <fcntl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace octrace::io::detail {

double hdf5OpenDeadline() {
    if (const char* s = std::getenv("OCTRACE_HDF5_OPEN_SECONDS")) {
        char* end = nullptr;
        double v = std::strtod(s, &end);
        if (end != s && *end == '\0' && std::isfinite(v) && v > 0.0) return v;
        log::warning("OCTRACE_HDF5_OPEN_SECONDS='" + std::string(s) + "' is not a positive number; using 60");
    }
    return 60.0;
}

namespace {

// The child's exit statuses; any other one means the child did not get to its own exit.
constexpr int kProbeReturned = 0;
constexpr int kProbeThrew = 86;

std::string seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", s);
    return buf;
}

}  // namespace

void probeInChild(const std::string& path, const std::string& what, double limit, const std::function<void()>& probe) {
    pid_t pid = fork();
    if (pid < 0) {
        log::debug("cannot fork to guard " + what + " of " + path + " (" + std::strerror(errno) + "); reading it unguarded");
        return;
    }
    if (pid == 0) {
        // The child: only the calling thread exists. It never logs (the sink may belong to a
        // GUI) and leaves with _exit, so no destructor or atexit handler of the parent's runs.
        log::setLevel(log::Level::Quiet);
        // Nor does anything it runs: its stderr goes nowhere, so that a library's messages or a
        // sanitizer's report about a corrupt file (an instrumented build) do not reach the
        // user's terminal; the parent says what happened in one line.
        const int devNull = open("/dev/null", O_WRONLY);
        if (devNull >= 0) dup2(devNull, STDERR_FILENO);
        int status = kProbeReturned;
        try {
            probe();
        } catch (...) {
            status = kProbeThrew;
        }
        _exit(status);
    }
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto pause = std::chrono::microseconds(200);
    bool said = false;
    for (;;) {
        int status = 0;
        pid_t r = waitpid(pid, &status, WNOHANG);
        if (r == pid) {
            if (WIFSIGNALED(status))
                throw FileError(path + ": reading " + what + " crashed (signal " + std::to_string(WTERMSIG(status)) +
                                ", in a child process octrace runs it in); the file is probably corrupt");
            // Any other exit: the library ended the child itself (abort handlers, a sanitizer's
            // report in an instrumented build).
            const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
            if (code != kProbeReturned && code != kProbeThrew)
                throw FileError(path + ": reading " + what + " crashed (exit status " + std::to_string(code) +
                                ", in a child process octrace runs it in); the file is probably corrupt");
            return;
        }
        if (r < 0 && errno != EINTR) {
            log::debug("lost the child guarding " + what + " of " + path + " (" + std::strerror(errno) + ")");
            return;
        }
        double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        if (elapsed >= limit) {
            kill(pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            throw FileError(path + ": reading " + what + " did not finish within " + seconds(limit) +
                            " s; the file is probably corrupt (HDF5 can loop forever on a damaged one). A slow "
                            "disk? Allow more with OCTRACE_HDF5_OPEN_SECONDS");
        }
        if (!said && elapsed >= 2.0) {
            log::info(path + ": still reading " + what + " (giving up after " + seconds(limit) + " s)");
            said = true;
        }
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(20000));
    }
}

}  // namespace octrace::io::detail
