#pragma once
// Runs the octrace executable as a user would and captures exit code, stdout and stderr.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace octrace::testcli {

struct Result {
    int code = -1;
    std::string out, err;
};

inline std::string quoteArg(const std::string& a) {
    std::string q = "'";
    for (char c : a) {
        if (c == '\'') q += "'\\''";
        else q += c;
    }
    return q + "'";
}

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

/// A scratch folder removed at the end of the test.
class Scratch {
public:
    Scratch() {
        static int n = 0;
        dir_ = std::filesystem::temp_directory_path() /
               ("octrace-cli-" + std::to_string(getpid()) + "-" + std::to_string(n++));
        std::filesystem::create_directories(dir_);
    }
    ~Scratch() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    const std::filesystem::path& dir() const { return dir_; }

private:
    std::filesystem::path dir_;
};

inline Result run(const std::vector<std::string>& args) {
    Scratch s;
    std::string cmd = quoteArg(OCTRACE_BINARY);
    // Appended piece by piece: `" " + std::string` makes gcc 12 warn (a -Wrestrict false positive).
    for (const auto& a : args) cmd.append(" ").append(quoteArg(a));
    cmd.append(" > ").append(quoteArg(s.path("stdout")));
    cmd.append(" 2> ").append(quoteArg(s.path("stderr")));
    cmd.append(" < /dev/null");
    int st = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
    r.out = slurp(s.path("stdout"));
    r.err = slurp(s.path("stderr"));
    return r;
}

/// `octrace ARGS...` started in the background; its stdout and stderr go to files in `logs`.
class Child {
public:
    Child(const std::vector<std::string>& args, const Scratch& logs) {
        std::vector<std::string> all{OCTRACE_BINARY};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (auto& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        const std::string out = logs.path("stdout"), err = logs.path("stderr");
        pid_ = ::fork();
        if (pid_ == 0) {
            // Only async-signal-safe calls between fork and exec.
            const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int in = ::open("/dev/null", O_RDONLY);
            if (o < 0 || e < 0 || in < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0 || ::dup2(in, 0) < 0) ::_exit(126);
            ::execv(argv[0], argv.data());
            ::_exit(127);
        }
    }
    ~Child() {
        if (pid_ > 0 && !reaped_) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;

    pid_t pid() const { return pid_; }
    /// Waits until the child ends (or, with `orStopped`, stops) and returns waitpid's status;
    /// `usage` (optional) receives what the child used (ru_maxrss: its peak resident memory).
    int wait(bool orStopped = false, rusage* usage = nullptr) {
        int status = 0;
        rusage ignored{};
        ::wait4(pid_, &status, orStopped ? WUNTRACED : 0, usage ? usage : &ignored);
        reaped_ = !(orStopped && WIFSTOPPED(status));
        return status;
    }
    /// True once the child has ended (without reaping it).
    bool ended() const {
        siginfo_t info{};
        return ::waitid(P_PID, id_t(pid_), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid != 0;
    }
    /// Resident memory in bytes (0 once it has ended).
    std::size_t residentBytes() const {
        std::ifstream in("/proc/" + std::to_string(pid_) + "/statm");
        std::size_t pages = 0, resident = 0;
        in >> pages >> resident;
        return resident * std::size_t(::sysconf(_SC_PAGESIZE));
    }

private:
    pid_t pid_ = -1;
    bool reaped_ = false;
};

inline std::string sharedData(const std::string& rel) { return std::string(OCTRACE_SHARED_DATA) + "/" + rel; }
inline bool haveShared(const std::string& rel) { return std::filesystem::exists(sharedData(rel)); }

/// Number of entries in a folder (to check that no temporary file is left behind).
inline int countEntries(const std::filesystem::path& dir) {
    int n = 0;
    for (auto& e : std::filesystem::directory_iterator(dir)) {
        (void)e;
        ++n;
    }
    return n;
}

}  // namespace octrace::testcli
