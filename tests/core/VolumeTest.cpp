// The volume form of the octree: built top-down from a field, its interior as terms, caps
// where the solid meets the grid's or the cube's faces, and its shell.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/Volume.h"
#include "octrace/util/Error.h"
#include "VolumeTestUtil.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace octrace;

namespace {

Octree volumeOf(const ScalarField& f, int depth, double iso, bool below = false, int threads = 0) {
    BuildOptions o{depth, iso, threads};
    o.form = OctreeForm::Volume;
    o.insideBelow = below;
    return buildOctree(f, o);
}

std::map<std::uint64_t, std::uint32_t> cellsAndNormals(const Octree& t) {
    std::map<std::uint64_t, std::uint32_t> m;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        m[(std::uint64_t(c.x) << 40) | (std::uint64_t(c.y) << 20) | std::uint64_t(c.z)] = t.voxels()[v].normal;
    });
    return m;
}

}  // namespace

TEST(VolumeOctree, ItsShellIsTheShellOctreeWhenTheSolidIsInsideTheGrid) {
    const ScalarField f = makeAnalyticField("sphere", 33);
    const Octree shell = buildShellOctree(f, {6, 0.0, 0});
    const Octree vol = volumeOf(f, 6, 0.0);
    EXPECT_EQ(vol.form, OctreeForm::Volume);
    EXPECT_NO_THROW(vol.validate());
    const Octree extracted = extractShell(vol);
    EXPECT_EQ(extracted.form, OctreeForm::Shell);
    EXPECT_NO_THROW(extracted.validate());
    EXPECT_EQ(cellsAndNormals(extracted), cellsAndNormals(shell));
    EXPECT_EQ(countVoxels(vol).boundary, shell.voxels().size());
    expectClosed(vol);
}

TEST(VolumeOctree, KeepsTheInteriorAsTermsAndCountsTheSphereVolume) {
    const ScalarField f = makeAnalyticField("sphere", 65);
    const int depth = 8;
    const Octree vol = volumeOf(f, depth, 0.0);
    const VoxelCount n = countVoxels(vol);
    // The sphere of radius 0.7 in the cube [-1,1]^3 of 2^8 voxels per edge.
    const double h = 2.0 / 256.0, exact = 4.0 / 3.0 * M_PI * std::pow(0.7, 3) / (h * h * h);
    EXPECT_NEAR(n.volume() / exact, 1.0, 0.01);
    // Terms above the voxel level hold most of the interior: far fewer slots than voxels.
    EXPECT_LT(double(vol.voxels().size()), 0.25 * double(n.interior + n.boundary));
    bool termAbove = false;
    vol.forEachAtLevel(depth - 3, [&](const ivec3& c, std::uint32_t) {
        termAbove = termAbove || cellState(vol, c * 8 + 3) == CellState::Interior;
    });
    EXPECT_TRUE(termAbove);
}

TEST(VolumeOctree, InsideBelowIsTheComplement) {
    const ScalarField f = makeAnalyticField("sphere", 17);
    const Octree above = volumeOf(f, 5, 0.0), below = volumeOf(f, 5, 0.0, true);
    EXPECT_TRUE(below.insideBelow);
    const int n = 1 << 5;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z) {
                const CellState a = cellState(above, {x, y, z}), b = cellState(below, {x, y, z});
                if (a == CellState::Interior) {
                    EXPECT_EQ(b, CellState::Empty);
                }
                if (a == CellState::Empty) {
                    EXPECT_NE(b, CellState::Empty);
                }
                if (b == CellState::Interior) {
                    EXPECT_EQ(a, CellState::Empty);
                }
            }
    expectClosed(below);
    // The outside of the sphere reaches the cube's faces: caps there, normals pointing out.
    std::uint32_t v = 0;
    ASSERT_EQ(cellState(below, {0, 16, 16}, &v), CellState::Boundary);
    EXPECT_LT(decodeNormal(below.voxels()[v].normal).x, -0.99f);
}

TEST(VolumeOctree, CapsWhereTheSolidMeetsTheGridAndTheMask) {
    // A slab |x| <= 0.5 across a grid that is half the cube in z: caps on the y faces (the
    // cube's) and on the z faces (the grid's), and around a masked hole.
    ScalarField f = sampleFunction("slab", {33, 33, 17}, {-1, -1, -0.5}, {1.0 / 16, 1.0 / 16, 1.0 / 16},
                                   [](const dvec3& p) { return float(0.5 - std::abs(p.x)); });
    f.valid.assign(f.values.size(), 1);
    f.valid[f.index(16, 16, 8)] = 0;
    const Octree vol = volumeOf(f, 5, 0.0);
    EXPECT_NO_THROW(vol.validate());
    expectClosed(vol);
    auto normalAt = [&](ivec3 c) {
        std::uint32_t v = 0;
        EXPECT_EQ(cellState(vol, c, &v), CellState::Boundary) << c.x << "," << c.y << "," << c.z;
        return v == 0xFFFFFFFFu ? vec3(0.0f) : decodeNormal(vol.voxels()[v].normal);
    };
    EXPECT_GT(normalAt({16, 31, 16}).y, 0.99f);   // the cube's +y face
    EXPECT_LT(normalAt({16, 10, 8}).z, -0.99f);   // the grid's lowest z cells
    EXPECT_GT(normalAt({16, 10, 23}).z, 0.99f);   // its highest
    EXPECT_EQ(cellState(vol, {16, 10, 7}), CellState::Empty);  // below the grid
    EXPECT_EQ(cellState(vol, {16, 16, 16}), CellState::Empty);  // a corner is the masked sample
    const vec3 hole = normalAt({16, 14, 16});  // beside the hole: the cap faces +y, towards it
    EXPECT_GT(hole.y, 0.99f);
    EXPECT_NO_THROW(extractShell(vol).validate());
}

TEST(VolumeOctree, DoesNotDependOnTheThreads) {
    const ScalarField f = makeAnalyticField("torus", 33);
    expectSameOctree(volumeOf(f, 7, 0.0, false, 1), volumeOf(f, 7, 0.0, false, 0));
}
