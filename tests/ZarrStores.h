#pragma once
// The Levitus Zarr stores of the io and CLI tests (about 50 MB, too large to commit): made on
// first use by tests/data/zarr/make_zarr_stores.py into the build tree (OCTRACE_ZARR_STORES),
// again whenever the script changes. Test processes may run in parallel: each makes the stores
// in a folder of its own and renames it into place; the first rename wins.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace octrace::test {

inline std::string readText(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The folder holding the stores made from `levitus`, or "" with `why` saying what is missing
/// (`unavailable` true: xarray, zarr or gdalmdimtranslate absent) or what failed.
inline std::string zarrStores(const std::string& levitus, std::string& why, bool& unavailable) {
    namespace fs = std::filesystem;
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    const fs::path dir(OCTRACE_ZARR_STORES);
    const fs::path script = fs::path(OCTRACE_TEST_DATA) / "zarr" / "make_zarr_stores.py";
    const std::string wanted = readText(script);
    unavailable = false;
    if (fs::exists(dir / "made_by.py") && readText(dir / "made_by.py") == wanted) return dir.string();
    const fs::path tmp = dir.string() + ".tmp." + std::to_string(::getpid());
    std::error_code ec;
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp);
    const fs::path log = tmp.string() + ".log";
    const std::string command = std::string("'") + OCTRACE_TEST_PYTHON + "' '" + script.string() + "' levitus '" +
                                levitus + "' '" + tmp.string() + "' >'" + log.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code != 0) {
        why = "make_zarr_stores.py failed (exit " + std::to_string(code) + "): " + readText(log);
        unavailable = code == 77;
        fs::remove_all(tmp, ec);
        fs::remove(log, ec);
        return {};
    }
    fs::remove(log, ec);
    fs::copy_file(script, tmp / "made_by.py");
    if (fs::exists(dir / "made_by.py") && readText(dir / "made_by.py") == wanted) {
        fs::remove_all(tmp, ec);  // another process was first
        return dir.string();
    }
    fs::remove_all(dir, ec);  // stale stores of an older script
    fs::rename(tmp, dir, ec);
    if (ec) fs::remove_all(tmp, ec);  // another process was first after all
    return dir.string();
}

}  // namespace octrace::test

/// Skips without the shared Levitus file or without xarray/zarr/gdalmdimtranslate, fails when
/// the script fails; defines `dir`, the folder of the stores, and `levitus`, the NetCDF file.
#define OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus)                                                         \
    const std::string levitus = std::string(OCTRACE_SHARED_DATA) + "/ocean/levitus_climatology.cdf";      \
    if (!std::filesystem::exists(levitus)) GTEST_SKIP() << "shared data absent: " << levitus;             \
    std::string dir##Why;                                                                                  \
    bool dir##Unavailable = false;                                                                         \
    const std::string dir = ::octrace::test::zarrStores(levitus, dir##Why, dir##Unavailable);             \
    if (dir.empty() && dir##Unavailable) GTEST_SKIP() << dir##Why;                                         \
    ASSERT_FALSE(dir.empty()) << dir##Why
