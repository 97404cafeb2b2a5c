// Relief rasters for the relief solid: ETOPO20 and a GeoTIFF DEM from ../shared/data, a CF file
// with a depth variable stored north first, and the files that are not reliefs.
#include "octrace/io/ReliefReader.h"
#include "octrace/util/Error.h"

#include "CfFileWriter.h"
#include "IoTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace octrace;

namespace {
/// Height at the raster point nearest (lon, lat).
float heightNear(const ReliefRaster& r, double lon, double lat) {
    return r.at(int(std::lround((lon - r.u0) / r.du)), int(std::lround((lat - r.v0) / r.dv)));
}
}  // namespace

TEST(ReliefReader, ReadsEtopo20WithIncreasingAxesInMetres) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/etopo20.cdf");
    const ReliefRaster r = io::readRelief(path);
    EXPECT_EQ(r.nx, 1081);
    EXPECT_EQ(r.ny, 540);
    EXPECT_NEAR(r.u0, 20.0 + 1.0 / 6.0, 1e-4);
    EXPECT_NEAR(r.du, 1.0 / 3.0, 1e-6);
    EXPECT_NEAR(r.v0, -90.0 + 1.0 / 6.0, 1e-4);
    EXPECT_NEAR(r.dv, 1.0 / 3.0, 1e-6);
    const auto [lo, hi] = std::minmax_element(r.heights.begin(), r.heights.end());
    EXPECT_NEAR(*lo, -9026.62f, 0.01f);  // `octrace info` gives the valid range
    EXPECT_NEAR(*hi, 6228.81f, 0.01f);
    EXPECT_GT(heightNear(r, 88.0, 32.0), 4000.0f);   // Tibet
    EXPECT_LT(heightNear(r, 200.0, 0.0), -3000.0f);  // the central Pacific
    EXPECT_GT(heightNear(r, 100.0, -80.0), 2000.0f);  // the East Antarctic plateau is south: rows run north
}

TEST(ReliefReader, ReadsAGeographicGeoTiffDem) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "city/lux_elev_srtm.tif");
    const ReliefRaster r = io::readRelief(path);
    EXPECT_EQ(r.nx, 95);
    EXPECT_EQ(r.ny, 90);
    EXPECT_GT(r.u0, 5.5);
    EXPECT_LT(r.u0 + (r.nx - 1) * r.du, 6.7);
    EXPECT_GT(r.v0, 49.3);
    EXPECT_LT(r.v0 + (r.ny - 1) * r.dv, 50.3);
    const auto valid = std::count_if(r.heights.begin(), r.heights.end(), [](float h) { return std::isfinite(h); });
    EXPECT_GT(valid, 4000);
    for (float h : r.heights)
        if (std::isfinite(h)) {
            EXPECT_TRUE(h > 100.0f && h < 700.0f) << h;
        }
}

TEST(ReliefReader, NegatesDepthsAndReversesRowsStoredNorthFirst) {
    test::TempDir dir;
    const std::string path = dir.file("depth.nc");
    {
        test::CfFileWriter w(path);
        w.coordinate("lat", {10.0, 5.0, 0.0}, {{"units", "degrees_north"}});
        w.coordinate("lon", {100.0, 101.0, 102.0, 103.0}, {{"units", "degrees_east"}});
        w.variable("depth", {"lat", "lon"}, GDT_Float32, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12},
                   {{"units", "km"}, {"positive", "down"}});
    }
    const ReliefRaster r = io::readRelief(path);
    ASSERT_EQ(r.nx, 4);
    ASSERT_EQ(r.ny, 3);
    EXPECT_DOUBLE_EQ(r.v0, 0.0);
    EXPECT_DOUBLE_EQ(r.dv, 5.0);
    EXPECT_FLOAT_EQ(r.at(0, 0), -9000.0f);  // lat 0 (stored last), lon 100: 9 km deep
    EXPECT_FLOAT_EQ(r.at(3, 2), -4000.0f);  // lat 10, lon 103
}

TEST(ReliefReader, RefusesWhatIsNotARelief) {
    test::TempDir dir;
    const std::string two = dir.file("two.nc"), hot = dir.file("hot.nc");
    for (const std::string& p : {two, hot}) {
        test::CfFileWriter w(p);
        w.coordinate("lat", {0.0, 1.0}, {{"units", "degrees_north"}});
        w.coordinate("lon", {0.0, 1.0}, {{"units", "degrees_east"}});
        w.variable("a", {"lat", "lon"}, GDT_Float32, {1, 2, 3, 4}, {{"units", p == hot ? "degC" : "m"}});
        if (p == two) w.variable("b", {"lat", "lon"}, GDT_Float32, {1, 2, 3, 4});
    }
    EXPECT_THROW_WITH(io::readRelief(two), InputError, "exactly one 2-D variable");
    EXPECT_THROW_WITH(io::readRelief(hot), InputError, "expected a length");
    EXPECT_THROW_WITH(io::readRelief(dir.file("none.nc")), InputError, "no such file");
    OCTRACE_SHARED_FILE_OR_SKIP(levitus, "ocean/levitus_climatology.cdf");
    EXPECT_THROW_WITH(io::readRelief(levitus), InputError, "exactly one 2-D variable");
}
