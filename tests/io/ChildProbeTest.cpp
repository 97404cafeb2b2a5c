// The child-process guard NetcdfFile puts around HDF5's reading of NetCDF-4 metadata
// (io/src/input/ChildProbe.h): a probe that never ends is killed at the deadline and refused, one that
// throws or returns lets the caller go on, one that dies from a signal is refused.
#include "input/ChildProbe.h"
#include "IoTestSupport.h"

#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include <unistd.h>

using namespace octrace;
using io::detail::probeInChild;

namespace {

// Sets an environment variable for the scope of a test.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) { setenv(name, value, 1); }
    ~ScopedEnv() { unsetenv(name_); }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* name_;
};

}  // namespace

TEST(ChildProbe, AProbeThatNeverEndsIsKilledAtTheDeadlineAndRefused) {
    auto start = std::chrono::steady_clock::now();
    EXPECT_THROW_WITH(probeInChild("x.nc", "the metadata", 0.3,
                                   [] {
                                       for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
                                   }),
                      FileError, "x.nc: reading the metadata did not finish within 0.3 s");
    double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_GE(waited, 0.3);
}

TEST(ChildProbe, AProbeThatReturnsOrThrowsLetsTheCallerGoOn) {
    EXPECT_NO_THROW(probeInChild("x.nc", "the metadata", 30.0, [] {}));
    EXPECT_NO_THROW(probeInChild("x.nc", "the metadata", 30.0, [] { throw std::runtime_error("refused"); }));
}

TEST(ChildProbe, AProbeThatDiesFromASignalOrEndsTheProcessItselfIsRefused) {
    EXPECT_THROW_WITH(probeInChild("x.nc", "the metadata", 30.0, [] { std::raise(SIGKILL); }), FileError,
                      "x.nc: reading the metadata crashed (signal 9");
    // As a sanitizer ends a process after its report (exit status 1) or a library calls exit().
    EXPECT_THROW_WITH(probeInChild("x.nc", "the metadata", 30.0, [] { _exit(1); }), FileError,
                      "x.nc: reading the metadata crashed (exit status 1");
}

TEST(ChildProbe, TheDeadlineComesFromTheEnvironmentAndFallsBackToSixtySeconds) {
    {
        ScopedEnv e("OCTRACE_HDF5_OPEN_SECONDS", "2.5");
        EXPECT_EQ(io::detail::hdf5OpenDeadline(), 2.5);
    }
    {
        ScopedEnv e("OCTRACE_HDF5_OPEN_SECONDS", "soon");
        EXPECT_EQ(io::detail::hdf5OpenDeadline(), 60.0);
    }
    EXPECT_EQ(io::detail::hdf5OpenDeadline(), 60.0);
}

// Found by fuzz_netcdf_cf (docs/dev/fuzzing.md): two corrupt NetCDF-4 files on which HDF5,
// asked by libnetcdf for a variable's dimension scales, converts a damaged variable-length
// attribute for hours. Both are refused once the deadline has passed.
TEST(NetcdfReader, RefusesNetcdf4FilesOnWhichHdf5NeverFinishesOpening) {
    ScopedEnv e("OCTRACE_HDF5_OPEN_SECONDS", "0.5");
    for (const char* file : {"invalid_hdf5_hang_dimension_scales.nc", "invalid_hdf5_hang_2.nc"}) {
        const std::string path = test::testData(std::string("invalid/") + file);
        EXPECT_THROW_WITH(io::NetcdfReader::read(path, {}), FileError,
                          path + ": reading the NetCDF-4 (HDF5) metadata did not finish within 0.5 s");
        EXPECT_THROW_WITH((void)io::NetcdfReader::describe(path, 1 << 20), FileError, "did not finish within 0.5 s");
    }
}

// Found by fuzz_netcdf_cf with the guard in place: on this file HDF5 (H5HG_read, while
// libnetcdf reads dimension scales) calls memcpy on overlapping ranges. Uninstrumented, HDF5
// then fails and GDAL refuses the file; in a sanitizer build AddressSanitizer ends the child
// after its report and the guard refuses the file. Either way one clean FileError.
TEST(NetcdfReader, RefusesTheNetcdf4FileOnWhichHdf5CopiesOverlappingMemory) {
    const std::string path = test::testData("invalid/invalid_hdf5_memcpy_overlap.nc");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, {}), FileError, "corrupt");
}

// The guard changes nothing for a sound NetCDF-4 file: the same field as its classic twin.
TEST(NetcdfReader, ReadsASoundNetcdf4FileThroughTheGuardLikeItsClassicTwin) {
    auto nc4 = io::NetcdfReader::read(test::testData("netcdf/dateline_cf_nc4.nc"), {});
    auto classic = io::NetcdfReader::read(test::testData("netcdf/dateline_cf.nc"), {});
    EXPECT_EQ(nc4.dims, classic.dims);
    EXPECT_EQ(nc4.values, classic.values);
}
