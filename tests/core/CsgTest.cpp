// CSG of volume octrees and primitive solids: volumes of analytic solids against their exact
// values, commutativity, cut faces' normals, closed results, solids and their parser.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/Volume.h"
#include "octrace/csg/Csg.h"
#include "octrace/util/Error.h"

#include "VolumeTestUtil.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;

namespace {

Octree volumeOf(const ScalarField& f, int depth) {
    BuildOptions o{depth, 0.0, 0};
    o.form = OctreeForm::Volume;
    return buildOctree(f, o);
}

/// The sphere of radius 0.7 at the origin, as a volume octree over [-1,1]^3.
const Octree& sphere8() {
    static const Octree t = volumeOf(makeAnalyticField("sphere", 65), 8);
    return t;
}

constexpr double kR = 0.7;
const double kSphere = 4.0 / 3.0 * M_PI * kR * kR * kR;
// The box [kLo, kHi]^3, its faces in the middle of voxels of sphere8(): a face on the boundary
// between voxels would be counted half a voxel layer off (countVoxels counts a boundary voxel
// as half inside, true on average over the faces' positions, not for one on a voxel boundary).
constexpr double kH = 2.0 / 256, kLo = -1 + 134.5 * kH, kHi = -1 + 243.5 * kH;
const double kBox = std::pow(kHi - kLo, 3);

/// Volume in world units from the voxel count.
double volume(const Octree& t) { return countVoxels(t).volume() * std::pow(t.voxelSize(), 3); }

Solid box() {
    Solid b;
    b.kind = Solid::Kind::Box;
    b.a = dvec3(kLo);
    b.b = dvec3(kHi);
    return b;
}

/// Exact volume of the sphere's part in x, y, z > kLo (kHi lies outside the sphere), by the
/// midpoint rule in y and z over the exact chord length in x (error far below 1e-5).
double sphereInBox() {
    const int n = 4000;
    const double step = (kR - kLo) / n;
    double v = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double y = kLo + (i + 0.5) * step, z = kLo + (j + 0.5) * step, q = kR * kR - y * y - z * z;
            if (q > kLo * kLo) v += std::sqrt(q) - kLo;
        }
    return v * step * step;
}

/// Exact volume of the lens where spheres of radii r1, r2 at distance d overlap.
double lens(double r1, double r2, double d) {
    return M_PI * std::pow(r1 + r2 - d, 2) * (d * d + 2 * d * (r1 + r2) - 3 * std::pow(r1 - r2, 2)) / (12 * d);
}

}  // namespace

TEST(Csg, SphereAndBoxVolumesAreWithinOnePercentAtDepth8) {
    const Octree& s = sphere8();
    const double i = sphereInBox();
    const Octree u = csg(CsgOperand::of(s), CsgOp::Union, CsgOperand::of(box()));
    const Octree x = csg(CsgOperand::of(s), CsgOp::Intersection, CsgOperand::of(box()));
    const Octree d = csg(CsgOperand::of(s), CsgOp::Difference, CsgOperand::of(box()));
    EXPECT_NEAR(volume(s) / kSphere, 1.0, 0.01);
    EXPECT_NEAR(volume(u) / (kSphere + kBox - i), 1.0, 0.01);
    EXPECT_NEAR(volume(x) / i, 1.0, 0.01);
    EXPECT_NEAR(volume(d) / (kSphere - i), 1.0, 0.01);
    for (const Octree* t : {&u, &x, &d}) {
        EXPECT_EQ(t->form, OctreeForm::Volume);
        EXPECT_EQ(t->depth, 8);
        EXPECT_NO_THROW(t->validate());
    }
    // The box the other way round: a box octree (from a field) minus a sphere solid.
    const ScalarField boxField = sampleFunction("box", {65, 65, 65}, {-1, -1, -1}, {1.0 / 32, 1.0 / 32, 1.0 / 32}, [](const dvec3& p) {
        return float(std::min({p.x - kLo, kHi - p.x, p.y - kLo, kHi - p.y, p.z - kLo, kHi - p.z}));
    });
    const Octree b = volumeOf(boxField, 8);
    EXPECT_NEAR(volume(b) / kBox, 1.0, 0.01);
    EXPECT_NEAR(volume(csg(CsgOperand::of(b), CsgOp::Difference, CsgOperand::of(parseSolid("sphere:0,0,0,0.7")))) / (kBox - i), 1.0, 0.01);
}

TEST(Csg, OctreesOfOtherDepthsAndExtentsMeetOnACommonCube) {
    // A second sphere (radius 0.4 at x = 0.45) from a field on its own small grid, at depth 6.
    const double r2 = 0.4, d = 0.45;
    const ScalarField f2 = sampleFunction("sphere2", {37, 37, 37}, {0.0, -0.45, -0.45}, {0.025, 0.025, 0.025},
                                          [&](const dvec3& p) { return float(r2 - glm::length(p - dvec3(d, 0, 0))); });
    const Octree s2 = volumeOf(f2, 6);
    EXPECT_NE(s2.cubeSide, sphere8().cubeSide);
    const Octree u = csg(CsgOperand::of(sphere8()), CsgOp::Union, CsgOperand::of(s2));
    EXPECT_EQ(u.cubeSide, 2.0);  // sphere8's cube holds both; its voxels are the finer
    EXPECT_EQ(u.depth, 8);
    const double both = lens(kR, r2, d), v2 = 4.0 / 3.0 * M_PI * r2 * r2 * r2;
    EXPECT_NEAR(volume(u) / (kSphere + v2 - both), 1.0, 0.01);
    EXPECT_NEAR(volume(csg(CsgOperand::of(sphere8()), CsgOp::Intersection, CsgOperand::of(s2))) / both, 1.0, 0.01);
    EXPECT_NEAR(volume(csg(CsgOperand::of(sphere8()), CsgOp::Difference, CsgOperand::of(s2))) / (kSphere - both), 1.0, 0.01);
    // What is left of the small sphere is a thin crescent (0.04): checked as a part of it.
    const double rest = volume(csg(CsgOperand::of(s2), CsgOp::Difference, CsgOperand::of(sphere8())));
    EXPECT_NEAR((rest + both) / v2, 1.0, 0.01);
    expectSameOctree(u, csg(CsgOperand::of(s2), CsgOp::Union, CsgOperand::of(sphere8())));
}

TEST(Csg, UnionAndIntersectionDoNotDependOnTheOperandOrder) {
    const Octree& s = sphere8();
    const Octree torus = volumeOf(makeAnalyticField("torus", 65), 7);  // same cube, another depth
    for (CsgOp op : {CsgOp::Union, CsgOp::Intersection}) {
        expectSameOctree(csg(CsgOperand::of(s), op, CsgOperand::of(box())), csg(CsgOperand::of(box()), op, CsgOperand::of(s)));
        expectSameOctree(csg(CsgOperand::of(s), op, CsgOperand::of(torus)), csg(CsgOperand::of(torus), op, CsgOperand::of(s)));
    }
}

TEST(Csg, CutFacesTakeTheirNormalsFromTheCuttingSolid) {
    const Octree d = csg(CsgOperand::of(sphere8()), CsgOp::Difference, CsgOperand::of(box()));
    // The box's face x = kLo runs through cells 134: the cut face, facing +x (into the box).
    std::uint32_t v = 0;
    ASSERT_EQ(cellState(d, {134, 150, 150}, &v), CellState::Boundary);
    EXPECT_GT(decodeNormal(d.voxels()[v].normal).x, 0.999f);
    EXPECT_EQ(cellState(d, {136, 150, 150}), CellState::Empty);
    EXPECT_EQ(cellState(d, {132, 150, 150}), CellState::Interior);
    // Kept below the plane z = 0 (cells 127 and down; cell 128 has corners on both sides):
    // the cut face points +z, out of the half-space.
    const Octree h = csg(CsgOperand::of(sphere8()), CsgOp::Intersection, CsgOperand::of(parseSolid("halfspace:0,0,0,0,0,1")));
    ASSERT_EQ(cellState(h, {128, 128, 128}, &v), CellState::Boundary);
    EXPECT_GT(decodeNormal(h.voxels()[v].normal).z, 0.999f);
    EXPECT_EQ(cellState(h, {128, 128, 127}), CellState::Interior);
    EXPECT_EQ(cellState(h, {128, 128, 129}), CellState::Empty);
    // The shell of the result is closed and drawable.
    EXPECT_NO_THROW(extractShell(d).validate());
}

TEST(Csg, ResultsAreClosedAndSolidsTouchingTheCubeGetCaps) {
    const Octree s = volumeOf(makeAnalyticField("sphere", 33), 5);
    const Octree u = csg(CsgOperand::of(s), CsgOp::Union, CsgOperand::of(parseSolid("cylinder:0,0,-2,0,0,2,0.3")));
    expectClosed(u);
    std::uint32_t v = 0;
    ASSERT_EQ(cellState(u, {16, 16, 31}, &v), CellState::Boundary);  // the cylinder leaves the cube at +z: a cap
    EXPECT_GT(decodeNormal(u.voxels()[v].normal).z, 0.99f);
    expectClosed(csg(CsgOperand::of(s), CsgOp::Difference, CsgOperand::of(parseSolid("sphere:0.5,0.5,0.5,0.5"))));
    expectClosed(csg(CsgOperand::of(s), CsgOp::Intersection, CsgOperand::of(parseSolid("box:-2,-2,-2,0.3,2,2"))));
}

TEST(Csg, RefusesWhatItCannotCombine) {
    EXPECT_THROW(csg(CsgOperand::of(box()), CsgOp::Union, CsgOperand::of(box())), UsageError);
    const Octree shell = buildShellOctree(makeAnalyticField("sphere", 17), {4, 0.0, 0});
    EXPECT_THROW(csg(CsgOperand::of(shell), CsgOp::Union, CsgOperand::of(box())), UsageError);
    EXPECT_THROW(csg(CsgOperand::of(sphere8()), CsgOp::Intersection, CsgOperand::of(parseSolid("sphere:5,5,5,1"))), EmptyResultError);
    EXPECT_EQ(parseCsgOp("minus"), CsgOp::Difference);
    EXPECT_THROW(parseCsgOp("xor"), UsageError);
}

TEST(Solid, ParsesEachKindAndRefusesBadSpecs) {
    const Solid c = parseSolid("cylinder:0,0,0,0,0,2,0.5");
    EXPECT_NEAR(c.distance(dvec3(0, 0, 1)), -0.5, 1e-12);
    EXPECT_NEAR(c.distance(dvec3(1, 0, 1)), 0.5, 1e-12);
    EXPECT_NEAR(c.distance(dvec3(0, 0, 3)), 1.0, 1e-12);
    EXPECT_NEAR(c.normal(dvec3(0.4, 0, 1)).x, 1.0, 1e-12);
    EXPECT_NEAR(c.normal(dvec3(0, 0.1, 1.95)).z, 1.0, 1e-12);
    const Solid h = parseSolid("halfspace:0,0,1,0,0,2");
    EXPECT_NEAR(h.distance(dvec3(5, 5, 3)), 2.0, 1e-12);
    EXPECT_EQ(h.describe(), "halfspace:0,0,1,0,0,1");
    EXPECT_NEAR(parseSolid("sphere:1,0,0,2").distance(dvec3(1, 0, 0)), -2.0, 1e-12);
    const Solid b = parseSolid("box:0,0,0,0.9,0.9,0.9");
    EXPECT_NEAR(b.distance(dvec3(0.45, 0.45, 0.1)), -0.1, 1e-12);
    EXPECT_NEAR(b.normal(dvec3(0.45, 0.45, 0.1)).z, -1.0, 1e-12);
    EXPECT_NEAR(b.distance(dvec3(1.2, 0.45, 0.45)), 0.3, 1e-12);
    for (const char* bad : {"box:1,2,3", "box:0,0,0,1,1,x", "box:1,0,0,0,1,1", "sphere:0,0,0,0", "sphere:0,0,0,-1",
                            "cylinder:0,0,0,0,0,0,1", "halfspace:0,0,0,0,0,0", "cone:0,0,0,1", "box:0,0,0,1,1,inf", "box:0,,0,1,1,1"})
        EXPECT_THROW(parseSolid(bad), UsageError) << bad;
    EXPECT_TRUE(isSolidSpec("box:1"));
    EXPECT_FALSE(isSolidSpec("head.nrrd"));
}
