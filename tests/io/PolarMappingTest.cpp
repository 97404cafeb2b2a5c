// The polar stereographic mapping of geographic grids near a pole (ScalarField::Geographic::pole,
// io/src/netcdf/GeoGrid polarPole, CurvilinearGrid's plane lattice): when it is chosen, that a
// lon/lat point lands at its projected position with its value, that the pole is filled, on a
// synthetic regular grid, the real Levitus atlas and the tripolar test file.
#include "CfFileWriter.h"
#include "IoTestSupport.h"

#include "octrace/build/PolarStereographic.h"
#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>

using namespace octrace;
using test::CfFileWriter;

namespace {

bool hasNote(const ScalarField& f, const std::string& text) {
    return std::any_of(f.notes.begin(), f.notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

io::FieldRequest regionRequest(double w, double e, double s, double n) {
    io::FieldRequest r;
    r.hasRegion = true;
    r.region[0] = w, r.region[1] = e, r.region[2] = s, r.region[3] = n;
    r.horizontalSamples = 129;
    return r;
}

// A regular 1-degree grid over 0.5..359.5 E, 60.5..89.5 N, three levels, whose temperature is
// its latitude plus the depth in km.
void writeLatitudeGrid(const std::string& path) {
    CfFileWriter w(path);
    std::vector<double> lon, lat, depth = {0, 100, 500}, temp;
    for (int i = 0; i < 360; ++i) lon.push_back(0.5 + i);
    for (int j = 0; j < 30; ++j) lat.push_back(60.5 + j);
    w.coordinate("depth", depth, {{"units", "m"}, {"positive", "down"}});
    w.coordinate("lat", lat, {{"units", "degrees_north"}});
    w.coordinate("lon", lon, {{"units", "degrees_east"}});
    for (double d : depth)
        for (double y : lat)
            for (std::size_t i = 0; i < lon.size(); ++i) temp.push_back(y + d / 1000.0);
    w.variable("temp", {"depth", "lat", "lon"}, GDT_Float32, temp, {{"units", "degC"}});
}

// The sample of the top level nearest the world position `p`.
std::size_t nearestTop(const ScalarField& f, dvec2 p) {
    const int i = int(std::lround((p.x - f.origin.x) / f.spacing.x)), j = int(std::lround((p.y - f.origin.y) / f.spacing.y));
    EXPECT_TRUE(i >= 0 && j >= 0 && i < f.dims.x && j < f.dims.y) << p.x << ", " << p.y;
    return f.index(std::clamp(i, 0, f.dims.x - 1), std::clamp(j, 0, f.dims.y - 1), f.dims.z - 1);
}

}  // namespace

// Auto: polar for a region in one hemisphere reaching 75 degrees, lon/lat for a mid-latitude or
// global one; map_projection forces either.
TEST(PolarMapping, ChosenForAPolarRegionAndNotForAMidLatitudeOne) {
    OCTRACE_SHARED_FILE_OR_SKIP(levitus, "ocean/levitus_climatology.cdf");
    auto pole = [&](io::FieldRequest r) {
        r.variable = "TEMP";
        return io::NetcdfReader::read(levitus, r).geographic.pole;
    };
    EXPECT_EQ(pole(regionRequest(-180, 180, 65, 90)), 1);
    EXPECT_EQ(pole(regionRequest(-30, 60, 60, 80)), 1);
    EXPECT_EQ(pole(regionRequest(-180, 180, -90, -60)), -1);
    EXPECT_EQ(pole(regionRequest(-70, -10, 20, 55)), 0);
    EXPECT_EQ(pole(regionRequest(-180, 180, -75, 88)), 0);  // both hemispheres
    EXPECT_EQ(pole(regionRequest(-180, 180, 60, 74)), 0);   // not 75 degrees
    io::FieldRequest whole;
    whole.horizontalSamples = 129;
    EXPECT_EQ(pole(whole), 0);
    io::FieldRequest r = regionRequest(-180, 180, 65, 90);
    r.projection = io::FieldRequest::Projection::LonLat;
    EXPECT_EQ(pole(r), 0);
    r = regionRequest(-70, -10, 20, 55);
    r.projection = io::FieldRequest::Projection::Polar;
    EXPECT_EQ(pole(r), 1);

    r = regionRequest(-180, 180, 65, 90);
    r.variable = "TEMP";
    const ScalarField f = io::NetcdfReader::read(levitus, r);
    EXPECT_TRUE(hasNote(f, "geographic: polar stereographic, north pole, true scale at 71 N, central meridian 0 (chosen "
                           "automatically"))
        << f.notes.front();
    EXPECT_TRUE(hasNote(f, "lattice in the polar stereographic plane")) << f.notes.back();
    EXPECT_FALSE(hasNote(f, "x = R (lon - lon0) cos(lat0)"));
}

// A known point lands at its projected position: 30 E, 80 N is rho = R (1 + sin 71) tan 5 deg =
// 1084.4 km from the pole, at x = rho sin 30, y = -rho cos 30 (central meridian 0, the disc of
// the region centred on the pole); its sample holds its latitude, and so does every sample.
TEST(PolarMapping, KnownPointLandsAtItsProjectedPositionWithItsValue) {
    test::TempDir dir;
    const std::string path = dir.file("lat.nc");
    writeLatitudeGrid(path);
    const ScalarField f = io::NetcdfReader::read(path, regionRequest(-180, 180, 65, 90));
    ASSERT_EQ(f.geographic.pole, 1);
    EXPECT_NEAR(f.geographic.x0, 0.0, 1e-6);
    EXPECT_NEAR(f.geographic.y0, 0.0, 1e-6);
    const double rho = 6371.0 * (1.0 + std::sin(71.0 * polar::kDeg)) * std::tan(5.0 * polar::kDeg);
    EXPECT_NEAR(rho, 1084.4, 0.05);
    const dvec2 p = polar::worldFromLonLat(f.geographic, 30.0, 80.0);
    EXPECT_NEAR(p.x, rho * 0.5, 1e-9);
    EXPECT_NEAR(p.y, -rho * std::sqrt(3.0) / 2.0, 1e-9);
    const dvec2 back = polar::lonLatFromWorld(f.geographic, p.x, p.y);
    EXPECT_NEAR(back.x, 30.0, 1e-9);
    EXPECT_NEAR(back.y, 80.0, 1e-9);
    // The lattice point nearest (30 E, 80 N) is within half a step (<= 0.2 degrees) of it.
    const std::size_t n = nearestTop(f, p);
    ASSERT_TRUE(f.isValid(n));
    EXPECT_NEAR(f.values[n], 80.0, 0.25);
    // Every sample inside the ring of source rows holds its own latitude; outside the region's
    // disc (the lattice's corners) nothing.
    std::size_t checked = 0;
    for (int j = 0; j < f.dims.y; ++j)
        for (int i = 0; i < f.dims.x; ++i) {
            const dvec3 w = f.worldFromGrid(i, j, f.dims.z - 1);
            const dvec2 ll = polar::lonLatFromWorld(f.geographic, w.x, w.y);
            const std::size_t k = f.index(i, j, f.dims.z - 1);
            if (ll.y < 65.0 - 1e-6) {
                EXPECT_FALSE(f.isValid(k)) << ll.x << ", " << ll.y;
                continue;
            }
            ASSERT_TRUE(f.isValid(k)) << ll.x << ", " << ll.y;
            if (ll.y > 89.5) continue;  // inside the last source row's ring: its mean, below
            EXPECT_NEAR(f.values[k], ll.y, 0.01) << ll.x << ", " << ll.y;
            ++checked;
        }
    EXPECT_GT(checked, 10000u);
}

// The pole is filled: on the synthetic grid with the ring's value (89.5), on Levitus and on the
// tripolar file (where the fold's cells cover it) with ocean at the surface.
TEST(PolarMapping, PoleIsFilled) {
    test::TempDir dir;
    const std::string path = dir.file("lat.nc");
    writeLatitudeGrid(path);
    const ScalarField f = io::NetcdfReader::read(path, regionRequest(-180, 180, 65, 90));
    const std::size_t n = nearestTop(f, polar::worldFromLonLat(f.geographic, 0.0, 90.0));
    ASSERT_TRUE(f.isValid(n));
    EXPECT_NEAR(f.values[n], 89.5, 1e-4);
    EXPECT_TRUE(hasNote(f, "the ring of points round the pole bridged across it"));

    OCTRACE_SHARED_FILE_OR_SKIP(levitus, "ocean/levitus_climatology.cdf");
    io::FieldRequest r = regionRequest(-180, 180, 65, 90);
    for (const std::string& file : {levitus, test::testData("netcdf/tripolar_global.nc")}) {
        r.variable = file == levitus ? "TEMP" : "";
        const ScalarField g = io::NetcdfReader::read(file, r);
        ASSERT_EQ(g.geographic.pole, 1) << file;
        // Every lattice point within 3 degrees of the pole holds ocean at the surface.
        std::size_t near = 0;
        for (int j = 0; j < g.dims.y; ++j)
            for (int i = 0; i < g.dims.x; ++i) {
                const dvec3 w = g.worldFromGrid(i, j, g.dims.z - 1);
                if (polar::lonLatFromWorld(g.geographic, w.x, w.y).y < 87.0) continue;
                ++near;
                EXPECT_TRUE(g.isValid(g.index(i, j, g.dims.z - 1))) << file << " at " << w.x << ", " << w.y;
            }
        EXPECT_GT(near, 10u) << file;
    }
}

// The tripolar file and the Levitus atlas, both on the polar mapping over the Arctic, agree
// sample for sample (the lattice is the same: same region, same step).
TEST(PolarMapping, TripolarArcticAgreesWithTheLevitusAtlas) {
    OCTRACE_SHARED_FILE_OR_SKIP(levitus, "ocean/levitus_climatology.cdf");
    io::FieldRequest r = regionRequest(-180, 180, 65, 90);
    r.verticalScale = 100.0;
    const ScalarField c = io::NetcdfReader::read(test::testData("netcdf/tripolar_global.nc"), r);
    r.variable = "TEMP";
    const ScalarField g = io::NetcdfReader::read(levitus, r);
    ASSERT_EQ(c.dims.z, g.dims.z);
    std::vector<double> diff;
    std::size_t both = 0, either = 0;
    for (int k = 0; k < c.dims.z; ++k)
        for (int j = 0; j < c.dims.y; ++j)
            for (int i = 0; i < c.dims.x; ++i) {
                const dvec3 w = c.worldFromGrid(i, j, k);
                const int gi = int(std::lround((w.x - g.origin.x) / g.spacing.x)), gj = int(std::lround((w.y - g.origin.y) / g.spacing.y));
                if (gi < 0 || gj < 0 || gi >= g.dims.x || gj >= g.dims.y) continue;
                const bool vc = c.isValid(c.index(i, j, k)), vg = g.isValid(g.index(gi, gj, k));
                both += vc && vg;
                either += vc || vg;
                if (vc && vg) diff.push_back(std::abs(c.values[c.index(i, j, k)] - g.values[g.index(gi, gj, k)]));
            }
    ASSERT_FALSE(diff.empty());
    std::nth_element(diff.begin(), diff.begin() + std::ptrdiff_t(diff.size() / 2), diff.end());
    EXPECT_LT(diff[diff.size() / 2], 0.3) << "median |tripolar - Levitus|";
    EXPECT_GT(double(both) / double(either), 0.9) << "ocean points in both / in either";
}
