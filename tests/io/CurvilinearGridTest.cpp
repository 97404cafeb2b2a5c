// Curvilinear grids (2-D longitude/latitude): resampled onto a regular lattice (io/src/netcdf/
// CurvilinearGrid), checked on fields linear in longitude and latitude (reproduced exactly by
// the inverse bilinear mapping of an affine grid), with land, across the dateline, and on the
// files tests/data/netcdf/make_curvilinear.py made from the real Levitus atlas against the atlas.
#include "CfFileWriter.h"
#include "IoTestSupport.h"

#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace octrace;
using test::CfFileWriter;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const std::vector<double> kDepth = {0, 100, 500};

bool hasNote(const ScalarField& f, const std::string& text) {
    return std::any_of(f.notes.begin(), f.notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

// Longitude (unwrapped as the mapping has it), latitude and depth in metres of sample (i, j, k).
struct Place {
    double lon, lat, depthM;
};
Place placeOf(const ScalarField& f, int i, int j, int k) {
    dvec3 w = f.worldFromGrid(i, j, k);
    const auto& g = f.geographic;
    const double R = ScalarField::Geographic::kEarthRadiusKm;
    return {g.lon0 + w.x / (R * std::cos(g.lat0 * kDeg) * kDeg), g.lat0 + w.y / (R * kDeg), -w.z / g.verticalScale * 1000.0};
}

// A 6 x 8 grid turned by about 11 degrees: lat = lat0 + j + 0.2 i, lon = lon0 + i - 0.2 j (wrapped
// into -180..180), temp = unwrapped lon + 10 lat + depth, with `land` (j, i) points filled.
void writeTurnedGrid(const std::string& path, double lon0, double lat0, bool coordinatesAttribute,
                     const std::vector<std::pair<int, int>>& land = {}) {
    CfFileWriter w(path);
    w.dimension("y", 6);
    w.dimension("x", 8);
    w.coordinate("depth", kDepth, {{"units", "m"}, {"positive", "down"}});
    std::vector<double> lat, lon, temp;
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 8; ++i) {
            lat.push_back(lat0 + j + 0.2 * i);
            lon.push_back(std::remainder(lon0 + i - 0.2 * j, 360.0));
        }
    for (double d : kDepth)
        for (int j = 0; j < 6; ++j)
            for (int i = 0; i < 8; ++i) {
                bool isLand = std::find(land.begin(), land.end(), std::make_pair(j, i)) != land.end();
                temp.push_back(isLand ? -999.0 : (lon0 + i - 0.2 * j) + 10.0 * (lat0 + j + 0.2 * i) + d);
            }
    w.variable("nav_lat", {"y", "x"}, GDT_Float64, lat, {{"units", "degrees_north"}});
    w.variable("nav_lon", {"y", "x"}, GDT_Float64, lon, {{"units", "degrees_east"}});
    std::map<std::string, std::string> a = {{"units", "degC"}};
    if (coordinatesAttribute) a["coordinates"] = "nav_lon nav_lat";
    auto t = w.variable("votemper", {"depth", "y", "x"}, GDT_Float32, temp, a);
    CfFileWriter::numbers(*t, "missing_value", GDT_Float32, {-999.0});
}

// Every valid sample equals lon + 10 lat + depth (lon unwrapped); returns how many are valid.
std::size_t expectLinear(const ScalarField& f, double tolerance = 2e-3) {
    std::size_t valid = 0;
    for (int k = 0; k < f.dims.z; ++k)
        for (int j = 0; j < f.dims.y; ++j)
            for (int i = 0; i < f.dims.x; ++i) {
                std::size_t n = f.index(i, j, k);
                if (!f.isValid(n)) continue;
                ++valid;
                Place p = placeOf(f, i, j, k);
                double want = (p.lon < 0.0 ? p.lon + 360.0 : p.lon) + 10.0 * p.lat + p.depthM;
                EXPECT_NEAR(f.values[n], want, tolerance) << "at " << p.lon << ", " << p.lat << ", " << p.depthM << " m";
            }
    return valid;
}

}  // namespace

// 2-D coordinates named by `coordinates` or, without it, found over the variable's dimensions:
// the field is resampled, and a field linear in longitude and latitude comes out exactly.
TEST(CurvilinearGrid, TurnedGridIsResampledAndALinearFieldComesOutExactly) {
    test::TempDir dir;
    for (bool attribute : {true, false}) {
        const std::string path = dir.file(attribute ? "turned.nc" : "turned_no_attribute.nc");
        writeTurnedGrid(path, 140.0, 40.0, attribute);
        SCOPED_TRACE(path);
        ScalarField f = io::NetcdfReader::read(path, {});
        ASSERT_TRUE(f.geographic.valid);
        EXPECT_TRUE(hasNote(f, "curvilinear grid: 2-D coordinates nav_lon(y, x) and nav_lat(y, x), source 8 x 6 points"));
        EXPECT_TRUE(hasNote(f, "by inverse bilinear mapping in each source cell, ocean corners only"));
        EXPECT_FALSE(hasNote(f, "periodic in x"));
        std::size_t valid = expectLinear(f);
        // The lattice covers the turned grid's bounding box; the corners outside it are empty.
        EXPECT_GT(valid, f.sampleCount() / 2);
        EXPECT_LT(valid, f.sampleCount());
        std::string info = io::NetcdfReader::describe(path);
        EXPECT_NE(info.find("curvilinear (2-D nav_lat nav_lon: resampled onto a regular lattice)"), std::string::npos) << info;
        EXPECT_EQ(info.find("nav_lat(y, x) Float64 [6 x 8], units 'degrees_north', curvilinear"), std::string::npos)
            << info;  // a coordinate is not itself curvilinear
        EXPECT_NE(info.find("note: curvilinear grid"), std::string::npos) << info;
    }
}

// Land: a lattice point takes only ocean corners and is land when less than half its weight is
// ocean; cells whose four corners are ocean still give the linear field exactly.
TEST(CurvilinearGrid, LandIsNeverInterpolatedAcross) {
    test::TempDir dir;
    const std::string path = dir.file("land.nc");
    writeTurnedGrid(path, 140.0, 40.0, true, {{2, 3}});
    const std::string sea = dir.file("sea.nc");
    writeTurnedGrid(sea, 140.0, 40.0, true);
    io::FieldRequest r;
    r.horizontalSamples = 41;
    ScalarField f = io::NetcdfReader::read(path, r), all = io::NetcdfReader::read(sea, r);
    ASSERT_EQ(f.dims, all.dims);
    const double landLon = 140.0 + 3 - 0.4, landLat = 40.0 + 2 + 0.6;
    std::size_t lost = 0;
    for (int k = 0; k < f.dims.z; ++k)
        for (int j = 0; j < f.dims.y; ++j)
            for (int i = 0; i < f.dims.x; ++i) {
                std::size_t n = f.index(i, j, k);
                Place p = placeOf(f, i, j, k);
                double d = std::hypot(p.lon - landLon, p.lat - landLat);  // in source cells, about
                if (d < 0.3) {
                    EXPECT_FALSE(f.isValid(n)) << "next to the land point: " << p.lon << ", " << p.lat;
                }
                if (d > 1.5) {
                    EXPECT_EQ(f.isValid(n), all.isValid(n)) << p.lon << ", " << p.lat;
                    if (f.isValid(n)) {
                        EXPECT_EQ(f.values[n], all.values[n]);
                    }
                }
                if (f.isValid(n) && d <= 1.5) {  // only ocean corners: within the ocean values around
                    EXPECT_GT(f.values[n], all.values[n] - 12.0f);
                    EXPECT_LT(f.values[n], all.values[n] + 12.0f);
                }
                lost += all.isValid(n) && !f.isValid(n);
            }
    EXPECT_GT(lost, 0u);
}

// A grid across the dateline (longitudes stored 176 .. 180, -180 .. -171): a region across it is
// filled without a gap or a smear at the seam.
TEST(CurvilinearGrid, GridAcrossTheDatelineIsResampledWithoutASeam) {
    test::TempDir dir;
    const std::string path = dir.file("dateline.nc");
    writeTurnedGrid(path, 177.0, -10.0, true);
    io::FieldRequest r;
    r.hasRegion = true;
    const double region[4] = {178.0, -178.0, -8.0, -6.0};  // inside the turned grid
    std::copy(region, region + 4, r.region);
    r.horizontalSamples = 9;  // 0.5 degrees: coarser than the quarter-cell limit
    ScalarField f = io::NetcdfReader::read(path, r);
    EXPECT_EQ(f.geographic.lon0, 180.0);
    EXPECT_EQ(expectLinear(f), f.sampleCount());  // every lattice point inside a cell: no gap
    EXPECT_EQ(f.dims.x, 9);
}

// The rotated-pole North Atlantic file: its 1-D rlon/rlat (grid_longitude/grid_latitude) give
// way to the 2-D true coordinates, and the resampled field agrees with the Levitus atlas it was
// made from, in values and in its land.
void expectAgreesWithLevitus(const std::string& file, const std::string& note, const double region[4], double tolerance,
                             double maskAgreement) {
    OCTRACE_SHARED_FILE_OR_SKIP(levitus, "ocean/levitus_climatology.cdf");
    io::FieldRequest r;
    r.hasRegion = true;
    std::copy(region, region + 4, r.region);
    r.verticalScale = 100.0;
    r.horizontalSamples = 129;
    ScalarField c = io::NetcdfReader::read(test::testData(file), r);
    r.variable = "TEMP";
    ScalarField g = io::NetcdfReader::read(levitus, r);
    EXPECT_TRUE(hasNote(c, note)) << file;
    EXPECT_EQ(c.geographic.lon0, g.geographic.lon0);
    EXPECT_EQ(c.geographic.lat0, g.geographic.lat0);
    ASSERT_EQ(c.dims.z, g.dims.z);
    std::vector<double> diff;
    std::size_t both = 0, either = 0;
    for (int k = 0; k < c.dims.z; ++k)
        for (int j = 0; j < c.dims.y; ++j)
            for (int i = 0; i < c.dims.x; ++i) {
                // The Levitus sample nearest this lattice point (same mapping, uniform 1-degree steps).
                dvec3 w = c.worldFromGrid(i, j, k);
                int gi = int(std::lround((w.x - g.origin.x) / g.spacing.x));
                int gj = int(std::lround((w.y - g.origin.y) / g.spacing.y));
                if (gi < 0 || gj < 0 || gi >= g.dims.x || gj >= g.dims.y) continue;
                bool vc = c.isValid(c.index(i, j, k)), vg = g.isValid(g.index(gi, gj, k));
                both += vc && vg;
                either += vc || vg;
                if (vc && vg) diff.push_back(std::abs(c.values[c.index(i, j, k)] - g.values[g.index(gi, gj, k)]));
            }
    ASSERT_FALSE(diff.empty());
    std::nth_element(diff.begin(), diff.begin() + std::ptrdiff_t(diff.size() / 2), diff.end());
    EXPECT_LT(diff[diff.size() / 2], tolerance) << file << ": median |curvilinear - Levitus|";
    EXPECT_GT(double(both) / double(either), maskAgreement) << file << ": ocean points in both / in either";
}

TEST(CurvilinearGrid, RotatedPoleFileAgreesWithTheLevitusAtlas) {
    const double region[4] = {-70.0, -10.0, 20.0, 55.0};
    expectAgreesWithLevitus("netcdf/rotated_natl.nc", "2-D coordinates lon(rlat, rlon) and lat(rlat, rlon), source 121 x 89",
                            region, 0.3, 0.9);
}

// The tripolar-like global file: x is periodic across its stored seam and the top row folds onto
// itself; the Arctic under the fold agrees with the atlas (no smear, no gap), as does the rest.
TEST(CurvilinearGrid, TripolarFileAgreesWithTheLevitusAtlasAcrossTheSeamAndUnderTheFold) {
    const double arctic[4] = {-180.0, 180.0, 70.0, 89.0};
    expectAgreesWithLevitus("netcdf/tripolar_global.nc", "periodic in x, tripolar north fold", arctic, 0.3, 0.85);
    const double pacific[4] = {150.0, -120.0, -40.0, 40.0};  // across the dateline and the file's seam
    expectAgreesWithLevitus("netcdf/tripolar_global.nc", "periodic in x, tripolar north fold", pacific, 0.3, 0.9);
}

// `horizontalSamples` (the octree's 2^depth + 1) sets the lattice along the larger extent.
TEST(CurvilinearGrid, LatticeFollowsTheRequestedResolution) {
    const std::string path = test::testData("netcdf/tripolar_global.nc");
    io::FieldRequest r;
    r.hasRegion = true;
    const double region[4] = {-60.0, 0.0, -20.0, 20.0};
    std::copy(region, region + 4, r.region);
    for (int n : {65, 129}) {
        r.horizontalSamples = n;
        ScalarField f = io::NetcdfReader::read(path, r);
        EXPECT_EQ(std::max(f.dims.x, f.dims.y), n);
        EXPECT_TRUE(hasNote(f, std::to_string(n) + " points along the larger extent (the octree's 2^depth + 1)"));
    }
}

// A curvilinear grid with terrain-following levels (a real ROMS file: 2-D lat_rho/lon_rho and
// s_rho): refused by name rather than drawn with sigma read as a depth in metres.
// A curvilinear grid with a parametric vertical coordinate: each source column's depths are
// resampled onto the lattice with the field's weights, so each lattice column has its own. On
// the turned grid with h linear in longitude and latitude (so the bilinear floor is exact) and
// temp equal to the depth of its native level, every lattice depth between a column's
// shallowest and deepest level comes back as its own depth, and the floor is h at that place.
TEST(CurvilinearGrid, ParametricVerticalCoordinateOnACurvilinearGridHasEachColumnsDepths) {
    test::TempDir dir;
    const std::string path = dir.file("curvilinear_sigma.nc");
    const std::vector<double> sigma = {-0.875, -0.625, -0.375, -0.125};
    auto hAt = [](double lon, double lat) { return 100.0 + 40.0 * (lon - 140.0) + 25.0 * (lat - 40.0); };
    {
        CfFileWriter w(path);
        w.dimension("eta_rho", 6);
        w.dimension("xi_rho", 8);
        w.coordinate("sigma", sigma, {{"standard_name", "ocean_sigma_coordinate"}, {"positive", "up"},
                                      {"formula_terms", "sigma: sigma eta: zeta depth: h"}});
        std::vector<double> lat, lon, h, zeta(48, 0.0), temp;
        for (int j = 0; j < 6; ++j)
            for (int i = 0; i < 8; ++i) {
                lat.push_back(40.0 + j + 0.2 * i), lon.push_back(140.0 + i - 0.2 * j);
                h.push_back(hAt(lon.back(), lat.back()));
            }
        for (double s : sigma)
            for (double d : h) temp.push_back(-s * d);
        w.variable("lat_rho", {"eta_rho", "xi_rho"}, GDT_Float64, lat, {{"units", "degree_north"}});
        w.variable("lon_rho", {"eta_rho", "xi_rho"}, GDT_Float64, lon, {{"units", "degree_east"}});
        w.variable("h", {"eta_rho", "xi_rho"}, GDT_Float64, h, {{"units", "m"}, {"coordinates", "lon_rho lat_rho"}});
        w.variable("zeta", {"eta_rho", "xi_rho"}, GDT_Float64, zeta, {{"units", "m"}, {"coordinates", "lon_rho lat_rho"}});
        w.variable("temp", {"sigma", "eta_rho", "xi_rho"}, GDT_Float32, temp,
                   {{"units", "m"}, {"coordinates", "lon_rho lat_rho sigma"}});
    }
    io::FieldRequest req;
    req.variable = "temp";
    req.horizontalSamples = 33;
    ScalarField f = io::NetcdfReader::read(path, req);
    ASSERT_TRUE(f.geographic.valid);
    EXPECT_TRUE(hasNote(f, "curvilinear grid: 2-D coordinates lon_rho(eta_rho, xi_rho) and lat_rho(eta_rho, xi_rho)"));
    EXPECT_TRUE(hasNote(f, "vertical: parametric, ocean_sigma_coordinate (sigma: sigma, eta: zeta, depth: h)"));
    EXPECT_TRUE(hasNote(f, "each column's depths resampled onto the horizontal lattice with the field's weights"));
    ASSERT_GT(f.dims.z, 4);
    std::size_t inner = 0, columns = 0;
    for (int j = 0; j < f.dims.y; ++j)
        for (int i = 0; i < f.dims.x; ++i) {
            const Place top = placeOf(f, i, j, 0);
            const double h = hAt(top.lon, top.lat);
            bool any = false;
            for (int k = 0; k < f.dims.z; ++k) {
                const std::size_t n = f.index(i, j, k);
                const double d = placeOf(f, i, j, k).depthM;
                if (d > h + 1e-6) {
                    EXPECT_FALSE(f.isValid(n)) << "below the floor " << h << " m: " << d << " m";
                }
                if (!f.isValid(n)) continue;
                any = true;
                if (d >= 0.125 * h + 1e-6 && d <= 0.875 * h - 1e-6) {  // between the native levels: linear, exact
                    EXPECT_NEAR(f.values[n], d, 1e-3 * h) << top.lon << ", " << top.lat << ", " << d << " m";
                    ++inner;
                }
            }
            columns += any;
        }
    EXPECT_GT(columns, std::size_t(f.dims.x * f.dims.y) / 2);
    EXPECT_GT(inner, columns / 2);
    // A known column: the lattice point nearest 143.4 E, 42.6 N (h = 301 m there) reaches its
    // floor: its deepest valid level lies within one lattice step above h.
    int bi = 0, bj = 0;
    for (int j = 0; j < f.dims.y; ++j)
        for (int i = 0; i < f.dims.x; ++i) {
            Place p = placeOf(f, i, j, 0), b = placeOf(f, bi, bj, 0);
            if (std::hypot(p.lon - 143.4, p.lat - 42.6) < std::hypot(b.lon - 143.4, b.lat - 42.6)) bi = i, bj = j;
        }
    const Place at = placeOf(f, bi, bj, 0);
    const double h = hAt(at.lon, at.lat);
    double deepest = -1.0, step = 0.0;
    for (int k = 0; k < f.dims.z; ++k)
        if (f.isValid(f.index(bi, bj, k))) {
            double d = placeOf(f, bi, bj, k).depthM;
            if (d > deepest) {
                step = k + 1 < f.dims.z ? std::abs(placeOf(f, bi, bj, k + 1).depthM - d) : 0.0;
                deepest = d;
            }
        }
    EXPECT_LE(deepest, h + 1e-6);
    EXPECT_GE(deepest, h - step - 1e-6) << "h " << h << " at " << at.lon << ", " << at.lat;
    // Every level of the source and of the lattice is held while resampling: counted against
    // the memory budget (about 68 bytes per lattice point here, the lookup 32).
    req.memoryBudget = 50 * std::uint64_t(f.dims.x) * std::uint64_t(f.dims.y);
    EXPECT_THROW_WITH(io::NetcdfReader::read(path, req), LimitError,
                      "resampling the 4 levels of 'temp' and their depths onto the lattice");
}
