// 2-D fields (maps) read by the NetCDF reader for slices (FieldRequest::acceptPlanar), and the
// variables it never offers as fields: coordinates and cell bounds. Real data: ETOPO20 and the
// Levitus atlas; tests/data/netcdf/make_maps.py makes the Levitus-derived 2-D, OISST-like and
// bipolar-like files.
#include "IoTestSupport.h"

#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>

using namespace octrace;

namespace {

io::FieldRequest mapRequest(const std::string& variable = "") {
    io::FieldRequest r;
    r.variable = variable;
    r.acceptPlanar = true;
    return r;
}

bool hasNote(const ScalarField& f, const std::string& text) {
    return std::any_of(f.notes.begin(), f.notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

// The sample of `f` (a whole-grid geographic field) nearest to lon, lat at grid level k.
float valueAt(const ScalarField& f, double lonDeg, double latDeg, int k) {
    const double kmPerDegree = ScalarField::Geographic::kEarthRadiusKm * 3.14159265358979323846 / 180.0;
    const double x = (std::remainder(lonDeg - f.geographic.lon0, 360.0)) * kmPerDegree * std::cos(f.geographic.lat0 * 3.14159265358979323846 / 180.0);
    const double y = (latDeg - f.geographic.lat0) * kmPerDegree;
    const int i = int(std::lround((x - f.origin.x) / f.spacing.x)), j = int(std::lround((y - f.origin.y) / f.spacing.y));
    const std::size_t idx = f.index(i, j, k);
    return f.isValid(idx) ? f.values[idx] : NAN;
}

}  // namespace

TEST(NetcdfMap, Etopo20IsReadAsAMapOfOneLevelAtTheSurface) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/etopo20.cdf");
    const ScalarField f = io::NetcdfReader::read(path, mapRequest());  // ROSE, the only 2-D variable
    EXPECT_EQ(f.name, "ROSE");
    EXPECT_TRUE(f.planar);
    EXPECT_TRUE(f.geographic.valid);
    EXPECT_EQ(f.dims.z, 1);
    EXPECT_EQ(f.dims.y, 540);
    EXPECT_GE(f.dims.x, 1080);
    EXPECT_EQ(f.origin.z, 0.0);  // the sea surface
    EXPECT_TRUE(hasNote(f, "2-D field: read as a map at the surface (no vertical dimension)")) << f.notes.front();
    const auto [lo, hi] = f.validRange();
    EXPECT_LT(lo, -9000.0f);  // ocean trenches
    EXPECT_GT(hi, 5000.0f);   // the Himalaya
    EXPECT_LT(valueAt(f, -150.0, 20.0, 0), -3000.0f);  // the Pacific north of Hawaii
    EXPECT_GT(valueAt(f, 88.0, 31.0, 0), 4000.0f);      // Tibet
}

TEST(NetcdfMap, TwoDimensionalFieldIsRefusedForASurfaceWithWhatToDo) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/etopo20.cdf");
    io::FieldRequest r;
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, r), InputError,
                      "no 3-D variable (variables: ROSE(ETOPO20Y, ETOPO20X1_1081)): a surface needs a 3-D field; draw the 2-D ROSE with slice");
    r.variable = "ROSE";
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, r), InputError,
                      "variable ROSE(ETOPO20Y, ETOPO20X1_1081) is a 2-D field (a map over ETOPO20Y and ETOPO20X1_1081): a "
                      "surface needs a 3-D field; draw a 2-D field with slice");
}

TEST(NetcdfMap, LevitusLevelZeroAsATwoDimensionalFileIsTheAtlasTopLevel) {
    OCTRACE_SHARED_FILE_OR_SKIP(levitus, "ocean/levitus_climatology.cdf");
    const ScalarField atlas = io::NetcdfReader::read(levitus, mapRequest("TEMP"));  // 3-D: not planar
    EXPECT_FALSE(atlas.planar);
    const ScalarField map = io::NetcdfReader::read(test::testData("netcdf/levitus_sst_2d.nc"), mapRequest());
    ASSERT_TRUE(map.planar);
    EXPECT_EQ(map.name, "sst");
    EXPECT_EQ(map.dims.x, atlas.dims.x);
    EXPECT_EQ(map.dims.y, atlas.dims.y);
    EXPECT_EQ(map.origin.x, atlas.origin.x);
    EXPECT_EQ(map.origin.y, atlas.origin.y);
    EXPECT_EQ(map.geographic.lon0, atlas.geographic.lon0);
    const int top = atlas.dims.z - 1;  // z increases up: the surface is the last level
    std::size_t masked = 0;
    for (int j = 0; j < map.dims.y; ++j)
        for (int i = 0; i < map.dims.x; ++i) {
            const std::size_t m = map.index(i, j, 0), a = atlas.index(i, j, top);
            ASSERT_EQ(map.isValid(m), atlas.isValid(a)) << i << "," << j;
            if (map.isValid(m)) { ASSERT_EQ(map.values[m], atlas.values[a]) << i << "," << j; }
            masked += !map.isValid(m);
        }
    EXPECT_GT(masked, 20000u);  // land
    EXPECT_LT(masked, 40000u);
}

TEST(NetcdfMap, OisstLikeSingleLevelIsAMapAtThatLevelWithTheTimeStepNoted) {
    OCTRACE_SHARED_FILE_OR_SKIP(levitus, "ocean/levitus_climatology.cdf");
    const ScalarField map = io::NetcdfReader::read(test::testData("netcdf/levitus_sst_2d.nc"), mapRequest());
    const ScalarField oisst = io::NetcdfReader::read(test::testData("netcdf/oisst_like_zlev.nc"), mapRequest());
    ASSERT_TRUE(oisst.planar);
    EXPECT_EQ(oisst.dims, map.dims);
    EXPECT_TRUE(hasNote(oisst, "2-D field: read as a map at 0 m depth (the one level of 'zlev')"));
    // Packed to 0.01 degC, longitudes 0.5..359.5 instead of 20.5..379.5: the same SST.
    const std::pair<double, double> points[] = {{-150.5, 20.5}, {-30.5, 40.5}, {60.5, -30.5}, {170.5, 0.5}};
    for (const auto& [lon, lat] : points) {
        SCOPED_TRACE(std::to_string(lon) + "," + std::to_string(lat));
        EXPECT_NEAR(valueAt(oisst, lon, lat, 0), valueAt(map, lon, lat, 0), 0.0051);
    }
    EXPECT_TRUE(std::isnan(valueAt(oisst, 20.5, 10.5, 0)));  // Africa: land masked
    // Asked for a surface, the single level is still a map.
    io::FieldRequest surface;
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("netcdf/oisst_like_zlev.nc"), surface), InputError,
                      "draw the 2-D sst with slice");
}

TEST(NetcdfMap, DescribeListsMapsBesideVolumesAndTheGridOfTheMap) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/etopo20.cdf");
    const std::string text = io::NetcdfReader::describe(path, io::FieldRequest{});
    EXPECT_NE(text.find("ROSE(ETOPO20Y, ETOPO20X1_1081) Float32 [540 x 1081]"), std::string::npos) << text;
    EXPECT_NE(text.find("2-D: a map, drawn by slice only"), std::string::npos) << text;
    EXPECT_NE(text.find("grid of the map ROSE (whole grid):"), std::string::npos) << text;
    EXPECT_NE(text.find(" x 540 x 1\n"), std::string::npos) << text;
}

TEST(NetcdfMap, CellBoundsAndCoordinatesOfABipolarGridAreNeverOfferedAsFields) {
    const std::string path = test::testData("netcdf/bipolar_like.nc");
    EXPECT_EQ(io::NetcdfReader::volumeVariables(path), std::vector<std::string>{"thetao"});  // not lon_bnds(y, x, 4)
    const std::string text = io::NetcdfReader::describe(path, io::FieldRequest{});
    const std::size_t fields = text.find("variables:\n"), aux = text.find("coordinates and cell bounds (not fields):\n");
    ASSERT_NE(fields, std::string::npos) << text;
    ASSERT_NE(aux, std::string::npos) << text;
    for (const char* v : {"tos(y, x)", "thetao(lev, y, x)"}) {
        const std::size_t at = text.find(std::string("  ") + v);
        EXPECT_TRUE(at > fields && at < aux) << v << " listed as a field\n" << text;
    }
    EXPECT_NE(text.find("  lon_bnds(y, x, vertices): the cell bounds of 'lon' (named by its `bounds` attribute)"), std::string::npos) << text;
    EXPECT_NE(text.find("  lat(y, x): a coordinate of 'tos' (named by its `coordinates` attribute)"), std::string::npos) << text;
    EXPECT_EQ(text.find("  lon_bnds(y, x, vertices) Float64"), std::string::npos) << "bounds described as a field\n" << text;
    // Asked by name: refused, saying what they are.
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, mapRequest("lon_bnds")), InputError,
                      "variable lon_bnds(y, x, vertices) is the cell bounds of 'lon' (named by its `bounds` attribute), not a "
                      "field to draw (fields: tos(y, x), thetao(lev, y, x))");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, mapRequest("lat")), InputError,
                      "variable lat(y, x) is a coordinate of 'tos' (named by its `coordinates` attribute), not a field to draw");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, mapRequest("lev")), InputError,
                      "variable lev(lev) is the coordinate variable of dimension 'lev', not a field to draw");
}

// The invalid-input corpus (tests/data/invalid/README.md).
TEST(NetcdfMap, RefusesAMapWhoseEverySampleIsMasked) {
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("invalid/invalid_map_all_masked.nc"), mapRequest()),
                      EmptyResultError, "variable 'sst' has no valid sample");
}

TEST(NetcdfMap, RefusesAFileOfZeroAndOneDimensionalVariablesOnly) {
    const std::string path = test::testData("invalid/invalid_no_field.nc");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, mapRequest()), InputError,
                      "no 3-D variable, nor a 2-D one to draw as a map (variables: temp(depth))");
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, mapRequest("temp")), InputError,
                      "variable temp(depth) has 1 dimension(s) longer than 1 besides time: nothing to draw (a map needs 2, a surface 3)");
    EXPECT_NE(io::NetcdfReader::describe(path, io::FieldRequest{}).find("no 3-D or 2-D variable: nothing to draw"), std::string::npos);
}

// A NEMO-like 2-D map on a curvilinear grid (make_curvilinear.py: sosstsst(time_counter, y, x)
// with nav_lat/nav_lon on the tripolar grid, the surface of tripolar_global.nc): read as a map
// on the resampled lattice, land masked, and the same samples as the 3-D file's top level
// resampled onto the same lattice (the same weights, the same ocean corners).
TEST(NetcdfMap, CurvilinearTwoDimensionalFieldIsAMapOnTheResampledLattice) {
    io::FieldRequest r = mapRequest();
    r.hasRegion = true;
    const double region[4] = {-100.0, 20.0, -60.0, 70.0};
    std::copy(region, region + 4, r.region);
    r.horizontalSamples = 241;
    ScalarField map = io::NetcdfReader::read(test::testData("netcdf/nemo_sst_2d.nc"), r);
    EXPECT_EQ(map.name, "sosstsst");
    EXPECT_TRUE(map.planar);
    EXPECT_EQ(map.dims.z, 1);
    EXPECT_TRUE(hasNote(map, "curvilinear grid: 2-D coordinates nav_lon(y, x) and nav_lat(y, x), source 240 x 113 points"));
    EXPECT_TRUE(hasNote(map, "tripolar north fold"));
    EXPECT_TRUE(hasNote(map, "2-D field: read as a map at the surface"));
    io::FieldRequest t = r;
    t.variable = "temp";
    t.acceptPlanar = false;
    t.hasDepthRange = true;
    t.depthRange[0] = 0.0;  // the top two levels, 0 and 10 m
    t.depthRange[1] = 10.0;
    ScalarField top = io::NetcdfReader::read(test::testData("netcdf/tripolar_global.nc"), t);
    ASSERT_EQ(top.dims.x, map.dims.x);
    ASSERT_EQ(top.dims.y, map.dims.y);
    std::size_t land = 0, sea = 0;
    for (int j = 0; j < map.dims.y; ++j)
        for (int i = 0; i < map.dims.x; ++i) {
            const std::size_t m = map.index(i, j, 0), n = top.index(i, j, top.dims.z - 1);
            ASSERT_EQ(map.isValid(m), top.isValid(n)) << i << ", " << j;
            if (!map.isValid(m)) {
                ++land;
                continue;
            }
            ++sea;
            EXPECT_NEAR(map.values[m], top.values[n], 1e-3) << i << ", " << j;  // int16 packed at 0.001 there
        }
    EXPECT_GT(land, map.sampleCount() / 5);  // the Americas, Africa, Europe
    EXPECT_GT(sea, map.sampleCount() / 3);
    // Without acceptPlanar (render, build) it is refused as every map is.
    EXPECT_THROW_WITH(io::NetcdfReader::read(test::testData("netcdf/nemo_sst_2d.nc"), io::FieldRequest{}), InputError,
                      "a surface needs a 3-D field");
}
