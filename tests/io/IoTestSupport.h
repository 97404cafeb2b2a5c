#pragma once
// Helpers shared by the io tests: data locations, requests and exception checks.
#include "octrace/io/FieldRequest.h"
#include "octrace/util/Log.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

namespace octrace::test {

/// Path of a file under the shared real-data folder, or "" when the folder is absent.
inline std::string sharedData(const std::string& relative) {
    std::filesystem::path p = std::filesystem::path(OCTRACE_SHARED_DATA) / relative;
    return std::filesystem::exists(p) ? p.string() : std::string();
}

/// Path of a file in tests/data.
inline std::string testData(const std::string& relative) {
    return (std::filesystem::path(OCTRACE_TEST_DATA) / relative).string();
}

/// A request for `variable` (empty: the default one) inside LON0,LON1,LAT0,LAT1 (degrees).
inline io::FieldRequest regionRequest(const std::string& variable, double lon0, double lon1, double lat0,
                                      double lat1) {
    io::FieldRequest r;
    r.variable = variable;
    r.hasRegion = true;
    r.region[0] = lon0;
    r.region[1] = lon1;
    r.region[2] = lat0;
    r.region[3] = lat1;
    return r;
}

/// A fresh empty folder for files a test writes; removed by the destructor.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() /
                ("octrace_io_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                 std::to_string(::getpid()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

/// Collects log warnings while alive (instead of printing them), then restores the default sink.
class LogCapture {
public:
    LogCapture() {
        log::setSink([this](log::Level level, const std::string& text) {
            if (level >= log::Level::Warning) warnings.push_back(text);
        });
    }
    ~LogCapture() { log::setSink({}); }
    LogCapture(const LogCapture&) = delete;
    LogCapture& operator=(const LogCapture&) = delete;
    std::vector<std::string> warnings;
};

}  // namespace octrace::test

/// Skips the test when the shared data file is absent; defines `path`.
#define OCTRACE_SHARED_FILE_OR_SKIP(path, relative)                                              \
    const std::string path = ::octrace::test::sharedData(relative);                              \
    if (path.empty()) GTEST_SKIP() << "shared data absent: " << OCTRACE_SHARED_DATA << "/" << relative

/// Expects `statement` to throw exactly `Type` (or a subclass) whose message contains `text`.
#define EXPECT_THROW_WITH(statement, Type, text)                                                 \
    do {                                                                                         \
        try {                                                                                    \
            statement;                                                                           \
            ADD_FAILURE() << "expected " #Type " containing '" << (text) << "', nothing thrown";  \
        } catch (const Type& e) {                                                                \
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos)                       \
                << "message '" << e.what() << "' lacks '" << (text) << "'";                      \
        } catch (const std::exception& e) {                                                      \
            ADD_FAILURE() << "expected " #Type ", got other exception: " << e.what();            \
        }                                                                                        \
    } while (0)
