#pragma once
// Shared by the libFuzzer targets of tests/fuzz: a private scratch folder and quiet logging.
// A target may let only octrace::Error escape its parser (caught in the target); anything
// else (a crash, a sanitizer report, another exception, a leak, a hang) is a finding.
#include "octrace/util/Log.h"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace octrace::fuzz {

/// Drops octrace's log messages (warnings about odd headers are expected by the thousand).
inline void quietLogs() { log::setLevel(log::Level::Quiet); }

/// The memory budget the readers get, as the CLI always gives one (--max-memory): a header
/// announcing more samples than that is refused, as a user would see it, instead of being
/// an out-of-memory finding (run.sh stops a target at 2 GiB). 64 MiB, not more: with
/// coverage instrumentation each sample costs about 55 ns in the per-sample loops (decoding,
/// validity), so the 175 million one-byte samples a 1 GiB budget let a header ask for took
/// 10 s per read, and fuzz_metaimage's two reads of an input passed run.sh's 10 s limit
/// (a CI smoke run of 2026-11-26). `octrace info` reads the same volume in 1 s (Release).
inline constexpr std::uint64_t kMemoryBudget = std::uint64_t(64) << 20;

/// A folder of its own under $TMPDIR, removed at exit.
class ScratchDir {
public:
    ScratchDir() {
        std::string base = (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + std::string("/octrace_fuzz_XXXXXX");
        if (!mkdtemp(base.data())) std::abort();
        dir_ = base;
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    /// Writes `size` bytes to `name` in the folder; returns its path.
    std::string write(const std::string& name, const void* data, std::size_t size) const {
        std::string p = path(name);
        std::ofstream out(p, std::ios::binary | std::ios::trunc);
        out.write(static_cast<const char*>(data), std::streamsize(size));
        if (!out) std::abort();
        return p;
    }

    /// Writes `size` bytes of a fixed pattern to `name`: a data file for detached headers.
    std::string writePattern(const std::string& name, std::size_t size) const {
        std::string bytes(size, '\0');
        for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>(i * 7 + 3);
        return write(name, bytes.data(), size);
    }

private:
    std::filesystem::path dir_;
};

}  // namespace octrace::fuzz
