#pragma once
// Runs the octrace executable as a user would and captures exit code, stdout and stderr.
#include <gtest/gtest.h>

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
    for (const auto& a : args) {
        cmd += ' ';
        cmd += quoteArg(a);
    }
    cmd += " > ";
    cmd += quoteArg(s.path("stdout"));
    cmd += " 2> ";
    cmd += quoteArg(s.path("stderr"));
    cmd += " < /dev/null";
    int st = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
    r.out = slurp(s.path("stdout"));
    r.err = slurp(s.path("stderr"));
    return r;
}

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
