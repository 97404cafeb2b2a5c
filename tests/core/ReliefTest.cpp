// The relief solid (csg/Relief.h): the ground under a known heightfield cut from a volume
// octree, its volume against the exact one, the cut faces' normals against the analytic ones;
// the geographic mapping against the coordinate contract.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/Volume.h"
#include "octrace/csg/Csg.h"
#include "octrace/csg/Relief.h"
#include "octrace/util/Error.h"

#include "VolumeTestUtil.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;

namespace {

constexpr double kR = 0.7;  // the analytic sphere's radius

/// The heightfield, in world units over [-1,1]^2, and its gradient.
double height(double x, double y) { return 0.25 * std::sin(2.0 * x + 0.4) * std::cos(1.5 * y) + 0.1 * x - 0.05; }
dvec3 upNormal(double x, double y) {
    const double hx = 0.5 * std::cos(2.0 * x + 0.4) * std::cos(1.5 * y) + 0.1;
    const double hy = -0.375 * std::sin(2.0 * x + 0.4) * std::sin(1.5 * y);
    return glm::normalize(dvec3(-hx, -hy, 1.0));
}

/// The heightfield sampled every 2/n over [-1,1]^2, world = raster space.
std::shared_ptr<const Relief> analyticRelief(int n) {
    ReliefRaster r;
    r.nx = r.ny = n + 1;
    r.u0 = r.v0 = -1.0;
    r.du = r.dv = 2.0 / n;
    r.source = "analytic";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) r.heights.push_back(float(height(-1.0 + i * r.du, -1.0 + j * r.dv)));
    return std::make_shared<const Relief>(std::move(r), ReliefMapping{});
}

/// Exact volume of the sphere's part below the heightfield: the midpoint rule over the
/// chord of each column (error far below 1e-4).
double sphereBelowHeight() {
    const int n = 3000;
    const double step = 2.0 * kR / n;
    double v = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = -kR + (i + 0.5) * step, y = -kR + (j + 0.5) * step, q = kR * kR - x * x - y * y;
            if (q <= 0.0) continue;
            const double c = std::sqrt(q);
            v += std::clamp(height(x, y) + c, 0.0, 2.0 * c);
        }
    return v * step * step;
}

double volume(const Octree& t) { return countVoxels(t).volume() * std::pow(t.voxelSize(), 3); }

const Octree& sphere8() {
    static const Octree t = [] {
        BuildOptions o{8, 0.0, 0};
        o.form = OctreeForm::Volume;
        return buildOctree(makeAnalyticField("sphere", 65), o);
    }();
    return t;
}

}  // namespace

TEST(Relief, SphereBelowAndAboveAHeightfieldAreWithinOnePercentAtDepth8) {
    const Solid ground = Solid::below(analyticRelief(512));
    const double below = sphereBelowHeight(), sphere = 4.0 / 3.0 * M_PI * kR * kR * kR;
    const Octree in = csg(CsgOperand::of(sphere8()), CsgOp::Intersection, CsgOperand::of(ground));
    const Octree out = csg(CsgOperand::of(sphere8()), CsgOp::Difference, CsgOperand::of(ground));
    EXPECT_NEAR(volume(in) / below, 1.0, 0.01);
    EXPECT_NEAR(volume(out) / (sphere - below), 1.0, 0.01);
    RecordProperty("below_ratio", std::to_string(volume(in) / below));
    RecordProperty("above_ratio", std::to_string(volume(out) / (sphere - below)));
    // Closed (checked cell by cell, so at depth 6: the sanitizer run is slow).
    BuildOptions o{6, 0.0, 0};
    o.form = OctreeForm::Volume;
    const Octree small = buildOctree(makeAnalyticField("sphere", 33), o);
    expectClosed(csg(CsgOperand::of(small), CsgOp::Intersection, CsgOperand::of(ground)));
    expectClosed(csg(CsgOperand::of(small), CsgOp::Difference, CsgOperand::of(ground)));
}

TEST(Relief, CutFacesTakeTheHeightfieldsNormals) {
    const Solid ground = Solid::below(analyticRelief(512));
    const Octree in = csg(CsgOperand::of(sphere8()), CsgOp::Intersection, CsgOperand::of(ground));
    const Octree out = csg(CsgOperand::of(sphere8()), CsgOp::Difference, CsgOperand::of(ground));
    // Boundary voxels well inside the sphere are on the cut face: their normals are the
    // heightfield's, up out of the ground (kept below) and down out of what is kept above.
    for (const Octree* t : {&in, &out}) {
        const double sign = t == &in ? 1.0 : -1.0;
        int checked = 0;
        double worst = 0.0;
        t->forEachVoxel([&](const ivec3& c, std::uint32_t v) {
            const dvec3 p = t->cubeOrigin + (dvec3(c) + 0.5) * t->voxelSize();
            if (cellState(*t, c) != CellState::Boundary || glm::length(p) > kR - 0.1) return;
            const double cosAngle = glm::dot(dvec3(decodeNormal(t->voxels()[v].normal)), sign * upNormal(p.x, p.y));
            worst = std::max(worst, std::acos(std::min(1.0, cosAngle)) * 180.0 / M_PI);
            ++checked;
        });
        EXPECT_GT(checked, 20000);
        RecordProperty(t == &in ? "worst_degrees_below" : "worst_degrees_above", std::to_string(worst));
        EXPECT_LT(worst, 1.0) << "degrees";
    }
}

TEST(Relief, HeightRangesBoundTheSurfaceAndClassifyOctants) {
    const auto r = analyticRelief(64);
    double zmin, zmax;
    bool complete;
    // Small rectangles are exact (bilinear extremes), larger ones conservative (the pyramid).
    for (double w : {0.01, 0.1, 0.5, 1.2}) {
        r->zRange(-0.3, -0.3 + w, -0.5, -0.5 + w, zmin, zmax, complete);
        EXPECT_TRUE(complete);
        double lo = 1e9, hi = -1e9;
        for (int i = 0; i <= 100; ++i)
            for (int j = 0; j <= 100; ++j) {
                const double z = r->surfaceZ(-0.3 + w * i / 100, -0.5 + w * j / 100);
                lo = std::min(lo, z), hi = std::max(hi, z);
            }
        EXPECT_LE(zmin, lo + 1e-9);
        EXPECT_GE(zmax, hi - 1e-9);
        if (w <= 0.1) {
            EXPECT_NEAR(zmin, lo, 2e-4);
            EXPECT_NEAR(zmax, hi, 2e-4);
        }
    }
    r->zRange(1.5, 2.0, 0.0, 0.5, zmin, zmax, complete);  // off the raster: no surface
    EXPECT_GT(zmin, zmax);
    EXPECT_FALSE(complete);
    const Solid g = Solid::below(r);
    EXPECT_EQ(g.classify(dvec3(-0.2, -0.2, -2.0), dvec3(0.2, 0.2, -1.0)), SolidCover::Inside);
    EXPECT_EQ(g.classify(dvec3(-0.2, -0.2, 1.0), dvec3(0.2, 0.2, 2.0)), SolidCover::Outside);
    EXPECT_EQ(g.classify(dvec3(-0.2, -0.2, -1.0), dvec3(0.2, 0.2, 1.0)), SolidCover::Mixed);
    EXPECT_EQ(g.classify(dvec3(0.9, -0.2, -2.0), dvec3(1.2, 0.2, -1.0)), SolidCover::Mixed);  // partly off the raster
    EXPECT_LT(g.distance(dvec3(0.1, 0.1, height(0.1, 0.1) - 0.01)), 0.0);
    EXPECT_GT(g.distance(dvec3(0.1, 0.1, height(0.1, 0.1) + 0.01)), 0.0);
    EXPECT_EQ(g.describe(), "relief:analytic");
}

TEST(Relief, GeographicReliefFollowsTheCoordinateContract) {
    // A global raster at 1 degree, height = 10 m * latitude + longitude (0..359), 0..360 stored twice.
    ReliefRaster r;
    r.nx = 361;
    r.ny = 181;
    r.u0 = 0.0, r.du = 1.0, r.v0 = -90.0, r.dv = 1.0;
    r.source = "globe";
    for (int j = 0; j < r.ny; ++j)
        for (int i = 0; i < r.nx; ++i) r.heights.push_back(float(10.0 * (j - 90) + (i % 360)));
    ScalarField::Geographic g;
    g.valid = true;
    g.lon0 = -170.0, g.lat0 = 40.0, g.verticalScale = 50.0;
    const auto relief = Relief::geographic(std::move(r), g);
    const double R = ScalarField::Geographic::kEarthRadiusKm, deg = M_PI / 180.0;
    auto worldZ = [&](double lon, double lat) {
        return relief->surfaceZ(R * (lon - g.lon0) * deg * std::cos(g.lat0 * deg), R * (lat - g.lat0) * deg);
    };
    // At 175 E (= -185, west of lon0 across the dateline) and 165 W: the stored longitudes 175, 195.
    EXPECT_NEAR(worldZ(-185.0, 40.0), (400.0 + 175.0) / 1000.0 * 50.0, 1e-6);
    EXPECT_NEAR(worldZ(-165.0, 41.0), (410.0 + 195.0) / 1000.0 * 50.0, 1e-6);
    ScalarField::Geographic none;
    ReliefRaster small;
    small.nx = small.ny = 2;
    small.heights.assign(4, 0.0f);
    EXPECT_THROW(Relief::geographic(std::move(small), none), UsageError);
    ReliefRaster empty;
    EXPECT_THROW(Relief(std::move(empty), ReliefMapping{}), UsageError);
}
