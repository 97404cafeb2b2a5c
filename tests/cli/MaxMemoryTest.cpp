// --max-memory: what does not fit the budget is refused up front (exit 1, one line naming the
// input, the need and the budget) before anything that size is allocated; the value itself is
// checked like any option (exit 2).
#include "CliRunner.h"

#include <algorithm>
#include <cstdint>

using namespace octrace::testcli;

namespace {
void expectOneLineRefusal(const Result& r, const std::string& expect) {
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << "expected '" << expect << "' in\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

/// Runs `octrace ARGS...` like run(), and also returns its peak resident memory in bytes.
Result runMeasured(const std::vector<std::string>& args, std::uint64_t& peakRss) {
    Scratch logs;
    Child child(args, logs);
    rusage usage{};
    const int status = child.wait(false, &usage);
    peakRss = std::uint64_t(usage.ru_maxrss) * 1024;
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    r.out = slurp(logs.path("stdout"));
    r.err = slurp(logs.path("stderr"));
    return r;
}

// What octrace needs to start and refuse (code, libraries, GDAL, VTK): far below the refused sizes.
constexpr std::uint64_t kSmall = std::uint64_t(200) << 20;
}  // namespace

TEST(MaxMemory, RefusesADepthThatDoesNotFitNamingTheLargestDepthThatDoes) {
    Scratch s;
    std::uint64_t peak = 0;
    Result r = runMeasured(
        {"render", "analytic:noise", "--iso", "0", "--depth", "12", "--max-memory", "128M", "-o", s.path("n.png")}, peak);
    expectOneLineRefusal(r, "octrace: error: analytic:noise(seed 1): the octree of 'noise' at depth 12 needs about ");
    EXPECT_NE(r.err.find("more than the memory budget of 128 MiB (--max-memory); the largest depth that fits is 9 (about "),
              std::string::npos)
        << r.err;
    EXPECT_EQ(countEntries(s.dir()), 0);
    // Refused from the estimate: nothing near the octree's size was allocated.
    EXPECT_LT(peak, kSmall);
    // The depth it names renders within the same budget.
    Result ok = run({"render", "analytic:noise", "--iso", "0", "--depth", "9", "--max-memory", "128M", "--size", "64x48",
                     "-o", s.path("n.png")});
    EXPECT_EQ(ok.code, 0) << ok.err;
}

// Smooth surfaces store 8 bytes of corner values per boundary voxel: the
// estimate counts them, so a budget that holds the depth-9 octree of voxels refuses its smooth
// surface, and the voxel surface of the same depth renders within it.
TEST(MaxMemory, CountsTheCornerValuesOfSmoothSurfaces) {
    Scratch s;
    std::uint64_t peak = 0;
    Result r = runMeasured({"render", "analytic:noise", "--iso", "0", "--depth", "9", "--surface", "smooth", "--max-memory",
                            "64M", "--size", "64x48", "-o", s.path("n.png")},
                           peak);
    expectOneLineRefusal(r, "octrace: error: analytic:noise(seed 1): the octree of 'noise' at depth 9 needs about ");
    EXPECT_NE(r.err.find(", per-voxel attributes "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the largest depth that fits is 8 (about "), std::string::npos) << r.err;
    EXPECT_LT(peak, kSmall);
    Result ok = run({"render", "analytic:noise", "--iso", "0", "--depth", "9", "--surface", "voxel", "--max-memory", "64M",
                     "--size", "64x48", "-o", s.path("n.png")});
    EXPECT_EQ(ok.code, 0) << ok.err;
}

// A 1024^3 float NRRD whose 4 GiB of data are there (a sparse file): refused from its header
// and the file's size, before a sample is decoded.
TEST(MaxMemory, RefusesAFieldTooLargeToReadBeforeAllocatingIt) {
    Scratch s;
    const std::string path = s.path("big.nrrd");
    const std::string header = "NRRD0004\ntype: float\ndimension: 3\nsizes: 1024 1024 1024\nendian: little\nencoding: raw\n\n";
    std::ofstream(path, std::ios::binary) << header;
    std::filesystem::resize_file(path, header.size() + (std::uintmax_t(4) << 30));
    const std::string expect = path + ": reading 1024x1024x1024 float samples needs about 9 GiB, more than the memory budget "
                                      "of 1 GiB (--max-memory)";
    std::uint64_t peak = 0;
    expectOneLineRefusal(runMeasured({"render", path, "--max-memory", "1G", "-o", s.path("big.png")}, peak), expect);
    EXPECT_LT(peak, kSmall);
    expectOneLineRefusal(runMeasured({"info", path, "--max-memory", "1G"}, peak), expect);
    EXPECT_LT(peak, kSmall);
    expectOneLineRefusal(
        runMeasured({"render", "analytic:sphere:1024", "--max-memory", "1G", "-o", s.path("big.png")}, peak),
        "analytic:sphere:1024: generating 1024^3 samples needs about 4 GiB, more than the memory budget of 1 GiB");
    EXPECT_LT(peak, kSmall);
    EXPECT_EQ(countEntries(s.dir()), 1);  // big.nrrd only
}

// The frames count too: 16384^2 pixels take 6.25 GiB a frame, and --verify keeps three.
TEST(MaxMemory, RefusesFramesTooLargeBeforeReadingTheInput) {
    Scratch s;
    std::uint64_t peak = 0;
    expectOneLineRefusal(runMeasured({"render", "/no/such/file.nc", "--size", "16384x16384", "--verify", "--max-memory", "8G",
                                      "-o", s.path("x.png")},
                                     peak),
                         "/no/such/file.nc: rendering 16384x16384 needs about 24.8 GiB, more than the memory budget of 8 GiB");
    EXPECT_LT(peak, kSmall);
    EXPECT_EQ(countEntries(s.dir()), 0);
}

TEST(MaxMemory, TakesBytesWithBinaryUnitsOrAShareOfTheMemoryAndRefusesAnythingElseAsAUsageError) {
    Scratch s;
    for (const char* ok : {"64M", "64m", "1.5G", "2GiB", "65536K", "50%", "100%", "1048576000", "1T"}) {
        Result r = run({"render", "analytic:sphere:17", "--depth", "5", "--size", "32x24", "--max-memory", ok, "-o",
                        s.path("x.png")});
        EXPECT_EQ(r.code, 0) << ok << "\n" << r.err;
    }
    for (const char* bad : {"0", "-1", "", "abc", "12 parsecs", "1KB", "101%", "0%", "0.5", "1e30", "nan", "inf", " 5"}) {
        Result r = run({"render", "analytic:sphere:17", "--max-memory", bad, "-o", s.path("x.png")});
        EXPECT_EQ(r.code, 2) << "'" << bad << "'\n" << r.err;
        EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("--help"), std::string::npos) << r.err;
    }
    Result h = run({"render", "--help"});
    EXPECT_NE(h.out.find("--max-memory SIZE"), std::string::npos) << h.out;
    EXPECT_NE(h.out.find("(default 50% of the physical memory)"), std::string::npos) << h.out;
    EXPECT_NE(run({"info", "--help"}).out.find("--max-memory SIZE"), std::string::npos);
}
