#include "IoTestSupport.h"

#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

using namespace octrace;

namespace {

// Reading tests/data/invalid/FILE throws FileError with `message` in it.
void expectCorpusRefusal(const std::string& file, const std::string& message) {
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/" + file), {}), FileError, message);
}

constexpr double kKmPerDegree = 6371.0 * std::numbers::pi / 180.0;

io::FieldRequest request(const std::string& var, double lon0, double lon1, double lat0, double lat1) {
    return test::regionRequest(var, lon0, lon1, lat0, lat1);
}

bool hasNote(const ScalarField& f, const std::string& text) {
    return std::any_of(f.notes.begin(), f.notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

// tests/data/netcdf/dateline_cf.cdl: temp = 100 k + (lat + 90) + lon360 / 1000.
float datelineValue(int storedDepth, double lat, double lon) {
    double lon360 = std::fmod(lon + 360.0, 360.0);
    return float(100.0 * storedDepth + (lat + 90.0) + lon360 / 1000.0);
}

}  // namespace

// Levitus climatology: 1-degree grid, longitudes 20.5..379.5, latitudes -89.5..89.5, 20 uneven
// depth levels 0..5000 m, missing value -1e10. Expected values checked with GDAL's Python API.
TEST(NetcdfReaderLevitus, NorthwestPacificRegionHasSixtyByFiftyByTwentyPoints) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    ScalarField f = io::NetcdfReader::read(path, request("TEMP", 120, 180, 10, 60));
    EXPECT_EQ(f.name, "TEMP");
    EXPECT_EQ(f.units, "DEG C");
    EXPECT_EQ(f.dims, ivec3(60, 50, 20));  // centres 120.5..179.5 E, 10.5..59.5 N
    EXPECT_FALSE(f.isRectilinear(0));
    EXPECT_FALSE(f.isRectilinear(1));
    double cos35 = std::cos(35.0 * std::numbers::pi / 180.0);
    EXPECT_NEAR(f.spacing.x, kKmPerDegree * cos35, 1e-6);
    EXPECT_NEAR(f.spacing.y, kKmPerDegree, 1e-6);
    EXPECT_NEAR(f.origin.x, -29.5 * kKmPerDegree * cos35, 1e-6);  // lon0 = 150
    EXPECT_NEAR(f.origin.y, -24.5 * kKmPerDegree, 1e-6);          // lat0 = 35
    EXPECT_TRUE(hasNote(f, "geographic: lon0=150 lat0=35"));
}

TEST(NetcdfReaderLevitus, DepthAxisIsRectilinearWithZIncreasingUpToTheSurface) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    ScalarField f = io::NetcdfReader::read(path, request("TEMP", 120, 180, 10, 60));
    ASSERT_TRUE(f.isRectilinear(2));
    const auto& z = f.coords[2];
    ASSERT_EQ(z.size(), 20u);
    EXPECT_TRUE(std::is_sorted(z.begin(), z.end()));
    // Default scale: 5 km of depth become a quarter of the larger (north-south) extent.
    double scale = 0.25 * 49.0 * kKmPerDegree / 5.0;
    EXPECT_NEAR(z.front(), -5.0 * scale, 1e-6);
    EXPECT_NEAR(z[1], -4.0 * scale, 1e-6);  // levels 5000, 4000, 3000, 2000, ... 0 m
    EXPECT_NEAR(z[3], -2.0 * scale, 1e-6);
    EXPECT_NEAR(z[18], -0.01 * scale, 1e-6);
    EXPECT_EQ(z.back(), 0.0);
    EXPECT_EQ(f.origin.z, 0.0);
    EXPECT_TRUE(hasNote(f, "vertical scale 272.4"));
}

TEST(NetcdfReaderLevitus, KnownValuesAndLandAndSeaFloorMasked) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    ScalarField f = io::NetcdfReader::read(path, request("TEMP", 120, 180, 10, 60));
    // 150.5E 35.5N (Kuroshio extension): 20.14 at the surface, 1.519 at 5000 m.
    EXPECT_FLOAT_EQ(f.values[f.index(30, 25, 19)], 20.14f);
    EXPECT_FLOAT_EQ(f.values[f.index(30, 25, 0)], 1.519f);
    EXPECT_FALSE(f.isValid(f.index(20, 26, 19)));  // 140.5E 36.5N is land (Honshu)
    // Sea of Japan at 135.5E 40.5N: water down to 2000 m, sea floor below.
    EXPECT_TRUE(f.isValid(f.index(15, 30, 3)));
    EXPECT_NEAR(f.values[f.index(15, 30, 3)], 0.113, 1e-6);
    EXPECT_FALSE(f.isValid(f.index(15, 30, 2)));
    EXPECT_EQ(f.validCount(), 43566u);
    auto [lo, hi] = f.validRange();
    EXPECT_NEAR(lo, -0.93, 1e-6);
    EXPECT_NEAR(hi, 28.849, 1e-6);
}

TEST(NetcdfReaderLevitus, DatelineRegionIsContiguousEitherWayItIsWritten) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    ScalarField a = io::NetcdfReader::read(path, request("TEMP", 170, -170, -10, 10));
    ScalarField b = io::NetcdfReader::read(path, request("TEMP", 170, 190, -10, 10));
    EXPECT_EQ(a.dims, ivec3(20, 20, 20));
    EXPECT_NEAR(a.origin.x, -9.5 * kKmPerDegree, 1e-6);  // lon0 = 180, lat0 = 0
    EXPECT_FLOAT_EQ(a.values[a.index(10, 10, 19)], 28.0f);    // 180.5E 0.5N
    EXPECT_FLOAT_EQ(a.values[a.index(19, 9, 19)], 27.577f);   // 189.5E (170.5W) 0.5S
    EXPECT_EQ(a.values, b.values);
    EXPECT_EQ(a.origin, b.origin);
}

TEST(NetcdfReaderLevitus, SeveralVariablesNeedAName) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, {}), InputError, "several 3-D variables (TEMP, SALT)");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, request("SOUND", 120, 180, 10, 60)), InputError,
                      "no variable 'SOUND' (variables: TEMP(ZAXLEVITR, YAXLEVITR, XAXLEVITR), SALT(");
}

TEST(NetcdfReaderLevitus, WholeGridIsCentredOnItsMiddle) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    io::FieldRequest r;
    r.variable = "SALT";
    ScalarField f = io::NetcdfReader::read(path, r);
    EXPECT_EQ(f.dims, ivec3(360, 180, 20));
    EXPECT_TRUE(hasNote(f, "geographic: lon0=200 lat0=0"));
    EXPECT_EQ(f.validCount(), 718725u);
}

TEST(NetcdfReaderLevitus, DescribeListsAxesVariablesAndRanges) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    std::string t = io::NetcdfReader::describe(path);
    for (const char* s : {"format: NetCDF-3 classic (CDF-1)", "XAXLEVITR = 360: longitude, units 'degrees_east', 20.5 .. 379.5, uniform step 1",
                          "ZAXLEVITR = 20: vertical (positive down), units 'METERS', 0 .. 5000, uneven",
                          "TEMP(ZAXLEVITR, YAXLEVITR, XAXLEVITR) Float32 [20 x 180 x 360], units 'DEG C', 'TEMPERATURE', "
                          "_FillValue -1e+10, missing_value -1e+10: valid range -2.02 .. 29.74 (718725 of 1296000 samples valid)",
                          "SALT(ZAXLEVITR, YAXLEVITR, XAXLEVITR)", "world bounds:", "z: rectilinear, 20 values",
                          "sound_speed: derived from TEMP and SALT with `var` sound_speed"})
        EXPECT_NE(t.find(s), std::string::npos) << "missing '" << s << "' in:\n" << t;
}

// Small CF fixture whose longitudes have their seam at the dateline.
TEST(NetcdfReader, DatelineRegionJoinsBothEndsOfTheFile) {
    ScalarField f = io::NetcdfReader::read(test::testData("netcdf/dateline_cf.nc"), request("", 170, -170, -30, 30));
    EXPECT_EQ(f.name, "temp");  // the only 3-D variable (time has length 1)
    EXPECT_EQ(f.units, "degC");
    ASSERT_EQ(f.dims, ivec3(4, 4, 3));
    EXPECT_NEAR(f.origin.x, -7.5 * kKmPerDegree, 1e-6);
    EXPECT_NEAR(f.spacing.x, 5.0 * kKmPerDegree, 1e-6);
    const double lons[] = {172.5, 177.5, -177.5, -172.5};
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                double lat = -30.0 + 20.0 * j;  // stored north to south, read south to north
                std::size_t idx = f.index(i, j, k);
                if (i == 2 && j == 0) {
                    EXPECT_FALSE(f.isValid(idx)) << "land point (_FillValue)";
                    continue;
                }
                ASSERT_TRUE(f.isValid(idx)) << i << " " << j << " " << k;
                EXPECT_FLOAT_EQ(f.values[idx], datelineValue(2 - k, lat, lons[i])) << i << " " << j << " " << k;
            }
}

TEST(NetcdfReader, DatelineRegionWrittenPastOneEightyIsTheSame) {
    std::string path = test::testData("netcdf/dateline_cf.nc");
    ScalarField a = io::NetcdfReader::read(path, request("temp", 170, -170, -30, 30));
    ScalarField b = io::NetcdfReader::read(path, request("temp", 170, 190, -30, 30));
    EXPECT_EQ(a.values, b.values);
    EXPECT_EQ(a.valid, b.valid);
    EXPECT_EQ(a.origin, b.origin);
}

TEST(NetcdfReader, UnevenDepthGivesRectilinearZAndExplicitScaleIsUsed) {
    io::FieldRequest r = request("temp", -10, 10, -30, 30);
    r.verticalScale = 100;
    ScalarField f = io::NetcdfReader::read(test::testData("netcdf/dateline_cf.nc"), r);
    ASSERT_TRUE(f.isRectilinear(2));
    EXPECT_EQ(f.coords[2], (std::vector<double>{-50.0, -10.0, 0.0}));
    EXPECT_TRUE(hasNote(f, "vertical scale 100 (requested)"));
}

TEST(NetcdfReader, NaNSamplesAndFillValuesAreInvalid) {
    ScalarField f = io::NetcdfReader::read(test::testData("netcdf/dateline_cf.nc"), {});
    EXPECT_EQ(f.dims, ivec3(72, 4, 3));
    EXPECT_EQ(f.validCount(), 72u * 4u * 3u - 4u);  // 3 land samples, 1 NaN
    EXPECT_FALSE(f.isValid(f.index(36, 2, 0)));      // lon 2.5, lat 10, deepest level: NaN
}

TEST(NetcdfReader, NetCdf4FileReadsLikeTheClassicOne) {
    ScalarField a = io::NetcdfReader::read(test::testData("netcdf/dateline_cf.nc"), {});
    ScalarField b = io::NetcdfReader::read(test::testData("netcdf/dateline_cf_nc4.nc"), {});
    EXPECT_EQ(a.dims, b.dims);
    EXPECT_EQ(a.valid, b.valid);
    for (std::size_t i = 0; i < a.values.size(); ++i)
        if (a.isValid(i)) {
            ASSERT_EQ(a.values[i], b.values[i]) << i;
        }
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.coords[2], b.coords[2]);
}

TEST(NetcdfReader, RegionWithOneLongitudeIsEmpty) {
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("netcdf/dateline_cf.nc"), request("temp", 0, 3, -30, 30)),
                      EmptyResultError, "region 0,3,-30,30 holds 1 longitude grid point(s), need at least 2");
}

TEST(NetcdfReader, MalformedRegionIsAUsageError) {
    std::string path = test::testData("netcdf/dateline_cf.nc");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, request("temp", 10, 10, 0, 5)), UsageError,
                      "longitude range 10..10 is empty");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, request("temp", 0, 10, 50, 40)), UsageError,
                      "LAT0 must be less than LAT1, got 50 and 40");
    io::FieldRequest negative;
    negative.verticalScale = -2;
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, negative), UsageError, "vertical scale must be positive");
}

TEST(NetcdfReader, FourDimensionalPackedVariableIsReadAtTheFirstTimeStep) {
    test::LogCapture log;
    ScalarField f = io::NetcdfReader::read(test::testData("netcdf/packed_4d.nc"), {});
    ASSERT_EQ(log.warnings.size(), 1u);
    EXPECT_NE(log.warnings[0].find("packed_4d.nc: variable 't': dimension 'time' (time): first of 2 steps used"), std::string::npos);
    EXPECT_EQ(f.name, "t");
    ASSERT_EQ(f.dims, ivec3(5, 3, 2));  // longitudes 0, 90, 180, 270, 360 (stored decreasing)
    EXPECT_NEAR(f.spacing.x, 90.0 * kKmPerDegree, 1e-6);
    // raw 0..29 in file order (lev, lat, lon), value = raw * 0.5 + 10
    auto expected = [](int lev, int lat, int lon) { return float((15 * lev + 5 * lat + lon) * 0.5 + 10.0); };
    EXPECT_EQ(f.values[f.index(0, 0, 0)], expected(0, 0, 4));  // deepest level (10 m), lon 0
    EXPECT_EQ(f.values[f.index(4, 0, 0)], expected(0, 0, 0));  // lon 360
    EXPECT_EQ(f.values[f.index(1, 2, 1)], expected(1, 2, 3));  // surface, lat 1, lon 90
    EXPECT_FALSE(f.isValid(f.index(0, 2, 1)));                 // _FillValue
    EXPECT_TRUE(hasNote(f, "dimension 'time' (time): first of 2 steps used"));
    EXPECT_TRUE(hasNote(f, "vertical axis 'lev' has no 'positive' attribute: taken as depth"));
}

TEST(NetcdfReader, RegionKeepsOneCopyOfARepeatedMeridian) {
    test::LogCapture log;  // the time-step warning is tested above
    ScalarField f = io::NetcdfReader::read(test::testData("netcdf/packed_4d.nc"), request("t", 200, 100, -1, 1));
    ASSERT_EQ(f.dims.x, 3);  // 270, 360 (= 0), 450 (= 90)
    EXPECT_TRUE(hasNote(f, "3 longitudes 270 .. 450"));
    EXPECT_NEAR(f.origin.x, -60.0 * kKmPerDegree, 1e-6);  // lon0 = 330
}

TEST(NetcdfReader, NonGeographicGridKeepsItsCoordinatesIncreasing) {
    ScalarField f = io::NetcdfReader::read(test::testData("netcdf/cartesian.nc"), {});
    EXPECT_EQ(f.name, "density");
    ASSERT_EQ(f.dims, ivec3(5, 4, 3));
    EXPECT_EQ(f.origin, dvec3(0.0, 10.0, 0.0));
    EXPECT_EQ(f.spacing, dvec3(2.0, 10.0, 1.0));  // y stored 40..10 is reversed; z has only indices
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 5; ++i) EXPECT_EQ(f.values[f.index(i, j, k)], float(100 * k + 10 * (3 - j) + i));
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("netcdf/cartesian.nc"), request("", 0, 10, 0, 10)),
                      InputError, "a region needs a longitude/latitude/depth grid");
}

// The invalid-input corpus (see tests/data/invalid/README.md).
TEST(NetcdfReader, RefusesUnknownVariableListingTheOthers) {
    io::FieldRequest r;
    r.variable = "TEMP";
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_no_variable.nc"), r), InputError,
                      "no variable 'TEMP' (variables: bathymetry(lat, lon))");
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_no_variable.nc"), {}), InputError,
                      "no 3-D variable (variables: bathymetry(lat, lon))");
}

TEST(NetcdfReader, RefusesVariableWithOnlyMissingValues) {
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_all_masked.nc"), {}), EmptyResultError,
                      "variable 'TEMP' has no valid sample");
}

TEST(NetcdfReader, RefusesTruncatedClassicFileInsteadOfReadingZeros) {
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_truncated.nc"), {}), FileError,
                      "NetCDF data truncated: the header places data up to byte 5000, the file has 3000 bytes");
}

// Found by fuzz_netcdf_classic_header (docs/dev/fuzzing.md): a name length of 2^64 - 16 is a
// seek of -16 bytes, and the header walker went round in circles, its list of dimensions
// growing until memory ran out.
TEST(NetcdfReader, RefusesAHeaderLengthBeyondTheFileInsteadOfLoopingForever) {
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_huge_name_length.nc"), {}), FileError,
                      "NetCDF header is truncated");
}

// Sizes whose product overflows 64 bits must not wrap around to a small end of data.
TEST(NetcdfReader, RefusesDimensionsWhoseByteCountOverflowsAsTruncated) {
    auto be32 = [](std::string& s, std::uint32_t v) {
        for (int i = 3; i >= 0; --i) s += char((v >> (8 * i)) & 0xff);
    };
    std::string b("CDF\x01", 4);
    be32(b, 0);                           // numrecs
    be32(b, 10);                          // NC_DIMENSION
    be32(b, 3);
    for (char n : {'x', 'y', 'z'}) {
        be32(b, 1);
        b += n;
        b += std::string(3, '\0');
        be32(b, 0xffffffffu);             // (2^32 - 1)^3 doubles: about 2^99 bytes
    }
    be32(b, 0), be32(b, 0);               // no global attributes
    be32(b, 11);                          // NC_VARIABLE
    be32(b, 1);
    be32(b, 1), b += "v", b += std::string(3, '\0');
    be32(b, 3), be32(b, 0), be32(b, 1), be32(b, 2);
    be32(b, 0), be32(b, 0);               // no attributes
    be32(b, 6);                           // NC_DOUBLE
    be32(b, 0xfffffff8u);                 // vsize (clamped)
    be32(b, std::uint32_t(b.size() + 4)); // begin: just after the header
    test::TempDir dir;
    const std::string path = dir.file("overflow.nc");
    std::ofstream(path, std::ios::binary).write(b.data(), std::streamsize(b.size()));
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, {}), FileError,
                      "NetCDF data truncated: the header places data up to byte 18446744073709551615");
}

// The absurd headers of tests/data/invalid: refused before anything of the announced size is
// allocated (the NetCDF-4 one used to make GDAL read 10^9 longitudes: 8 GB).
TEST(NetcdfReader, RefusesADimensionOfABillionPointsBeforeReadingItsCoordinates) {
    const std::string path = test::testData("invalid/invalid_billion_points_nc4.nc");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, {}), FileError,
                      path + ": dimension 'lon' has 1000000000 points, more than the 16777216 (2^24) octrace reads along one axis");
    EXPECT_THROW_WITH(io::NetcdfReader::describe(path), FileError, "dimension 'lon' has 1000000000 points");
}

TEST(NetcdfReader, RefusesClassicHeadersAnnouncingABillionPointsOrAnOverflowingSize) {
    expectCorpusRefusal("invalid_billion_points.nc",
                        "NetCDF data truncated: the header places data up to byte 16000000116, the file has 132 bytes");
    expectCorpusRefusal("invalid_size_overflow.nc",
                        "NetCDF data truncated: the header places data up to byte 18446744073709551615, the file has 200 bytes");
}

TEST(NetcdfReader, RefusesNaNRepeatedOrOverflowingCoordinates) {
    expectCorpusRefusal("invalid_nan_coordinate.nc", "latitude axis holds a non-finite value");
    expectCorpusRefusal("invalid_repeated_coordinate.nc",
                        "vertical values are not strictly monotonic (0.01 then 0.01 at index 1)");
    expectCorpusRefusal("invalid_infinite_extent.nc", "spacing along axis 0 must be positive and finite, is inf");
}

TEST(NetcdfReader, RefusesSamplesBeyondTheMemoryBudgetAndDescribeLeavesThemOut) {
    const std::string path = test::testData("netcdf/dateline_cf.nc");
    io::FieldRequest r;
    r.memoryBudget = 1024;
    // 72 x 4 x 3 samples of 13 bytes: a float, a mask byte, and GDAL's double.
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, r), LimitError,
                      path + ": reading 'temp' (72x4x3 samples) needs about 11 KiB, more than the memory budget of 1 KiB");
    r.memoryBudget = 72 * 4 * 3 * 13;
    EXPECT_EQ(io::NetcdfReader::read(path, r).dims, ivec3(72, 4, 3));
    std::string text = io::NetcdfReader::describe(path, 5000);
    EXPECT_NE(text.find("value range not computed (864 samples, over the memory budget)"), std::string::npos) << text;
    EXPECT_NE(text.find("landmask(lat, lon) Int16 [4 x 72], 2-D: a map, drawn by slice only: valid range"), std::string::npos) << text;
    EXPECT_NE(text.find("needs about 11 KiB, more than the memory budget of 4.9 KiB"), std::string::npos) << text;
}

TEST(NetcdfReader, RefusesTruncatedNetCdf4File) {
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_truncated_hdf5.nc"), {}), FileError,
                      "GDAL's netCDF driver cannot open it: the file is truncated or corrupt");
}

TEST(NetcdfReader, RefusesTextFileAsNotThisFormat) {
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_not_netcdf.nc"), {}), FormatNotSupported,
                      "not a NetCDF file: it starts with 'this is '");
}
