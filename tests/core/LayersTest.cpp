// Tests of the per-voxel attributes beside the octree: a second variable sampled at the voxels
// (sampleAtVoxels), the sea floor from a validity mask (solidFromMask) and surfaces merged into
// one octree with their materials (mergeShells).
#include "RenderTestUtil.h"

#include "octrace/build/AnalyticField.h"
#include "octrace/build/Layers.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

using namespace octrace;
using namespace octrace::test;

namespace {

ScalarField linearField(int n, bool maskTop) {
    const double s = 2.0 / double(n - 1);
    ScalarField f = sampleFunction("linear", ivec3(n), dvec3(-1.0), dvec3(s), [](const dvec3& p) { return float(p.x + 2.0 * p.y - 0.5 * p.z); });
    if (maskTop) {
        f.valid.assign(f.sampleCount(), 1);
        for (int k = 0; k < n; ++k)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    if (-1.0 + k * s > 0.4) f.valid[f.index(i, j, k)] = 0;
    }
    return f;
}

/// The sphere field with the samples below z = -0.45 masked, like a sea floor.
ScalarField sphereOverFloor() {
    ScalarField f = makeAnalyticField("sphere", 33);
    f.valid.assign(f.sampleCount(), 1);
    for (int k = 0; k < 33; ++k)
        for (int j = 0; j < 33; ++j)
            for (int i = 0; i < 33; ++i)
                if (f.worldFromGrid(i, j, k).z < -0.45) f.valid[f.index(i, j, k)] = 0;
    return f;
}

using CellKey = std::tuple<int, int, int>;
std::map<CellKey, std::uint32_t> cellsOf(const Octree& t) {
    std::map<CellKey, std::uint32_t> m;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t v) { m[{c.x, c.y, c.z}] = v; });
    return m;
}

}  // namespace

TEST(SampleAtVoxels, GivesALinearFieldsValueAtEveryVoxelCentre) {
    const Octree& t = sphereTree();
    const ScalarField f = linearField(17, false);
    const std::vector<float> v = sampleAtVoxels(t, f, 1);
    ASSERT_EQ(v.size(), t.voxels().size());
    const double h = t.voxelSize();
    std::size_t checked = 0;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t i) {
        const dvec3 p = t.cubeOrigin + (dvec3(c) + 0.5) * h;
        EXPECT_NEAR(v[i], p.x + 2.0 * p.y - 0.5 * p.z, 1e-5);
        ++checked;
    });
    EXPECT_GT(checked, 1000u);
    EXPECT_EQ(sampleAtVoxels(t, f, 0), v);  // threads do not change the result
}

TEST(SampleAtVoxels, IsNaNWhereTheInterpolationTouchesAMaskedSample) {
    const Octree& t = sphereTree();
    const ScalarField f = linearField(17, true);  // samples above z = 0.4 masked (spacing 0.125)
    const std::vector<float> v = sampleAtVoxels(t, f);
    std::size_t masked = 0, valid = 0;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t i) {
        const double z = t.cubeOrigin.z + (c.z + 0.5) * t.voxelSize();
        // The interpolation at z uses the samples at floor and ceil of z on the 0.125 lattice.
        const double upper = std::ceil((z + 1.0) / 0.125) * 0.125 - 1.0;
        if (upper > 0.4 + 1e-9) {
            EXPECT_TRUE(std::isnan(v[i])) << z;
            ++masked;
        } else {
            EXPECT_FALSE(std::isnan(v[i])) << z;
            ++valid;
        }
    });
    EXPECT_GT(masked, 100u);
    EXPECT_GT(valid, 100u);
}

TEST(SolidFromMask, IsOneAtMaskedSamplesAndZeroElsewhereWithTheSameGrid) {
    const ScalarField f = sphereOverFloor();
    const ScalarField s = solidFromMask(f);
    EXPECT_EQ(s.dims, f.dims);
    EXPECT_EQ(s.origin, f.origin);
    EXPECT_TRUE(s.valid.empty());
    for (std::size_t i = 0; i < f.sampleCount(); ++i) EXPECT_EQ(s.values[i], f.isValid(i) ? 0.0f : 1.0f);
    EXPECT_THROW(solidFromMask(makeAnalyticField("sphere", 9)), EmptyResultError);
}

TEST(MergeShells, KeepsEveryVoxelOfBothWithItsMaterialAndTheTopOnesWhereTheyMeet) {
    // A sphere over a torus that cuts through it, on the same grid: they share voxels.
    Octree top = buildShellOctree(makeAnalyticField("sphere", 33), {6, 0.0, 0});
    top.setVoxelValues(sampleAtVoxels(top, linearField(17, false)));
    Octree floor = buildShellOctree(makeAnalyticField("torus", 33), {6, 0.0, 0});
    setMaterial(floor, VoxelMaterial::Floor);
    const Octree m = mergeShells(top, floor);
    ASSERT_NO_THROW(m.validate());
    const auto a = cellsOf(top), b = cellsOf(floor), c = cellsOf(m);
    std::size_t shared = 0;
    for (const auto& [cell, v] : b) shared += a.count(cell);
    EXPECT_GT(shared, 0u);  // the rule for shared cells is exercised
    EXPECT_EQ(c.size(), a.size() + b.size() - shared);
    for (const auto& [cell, v] : c) {
        const auto ia = a.find(cell);
        if (ia != a.end()) {
            EXPECT_EQ(m.material(v), VoxelMaterial::Surface);
            EXPECT_EQ(m.voxels()[v].normal, top.voxels()[ia->second].normal);
            EXPECT_EQ(m.voxelValues()[v], top.voxelValues()[ia->second]);
        } else {
            const auto ib = b.find(cell);
            ASSERT_NE(ib, b.end());
            EXPECT_EQ(m.material(v), VoxelMaterial::Floor);
            EXPECT_EQ(m.voxels()[v].normal, floor.voxels()[ib->second].normal);
            EXPECT_TRUE(std::isnan(m.voxelValues()[v]));
        }
        EXPECT_EQ(m.findVoxel(ivec3(std::get<0>(cell), std::get<1>(cell), std::get<2>(cell))), v);
    }
    Octree other = buildShellOctree(makeAnalyticField("sphere", 33), {5, 0.0, 0});
    EXPECT_THROW(mergeShells(top, other), UsageError);
}

TEST(MergeShells, WithTheSolidUnderAMaskDrawsTheFloorUnderTheSurface) {
    const ScalarField f = sphereOverFloor();
    const Octree top = buildShellOctree(f, {6, 0.0, 0});
    Octree floor = buildShellOctree(solidFromMask(f), {6, 0.5, 0});
    setMaterial(floor, VoxelMaterial::Floor);
    const Octree m = mergeShells(top, floor);
    // The floor lies at the mask's edge, z in [-0.5, -0.4375] (samples every 0.0625).
    std::size_t floorVoxels = 0;
    m.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        if (m.material(v) != VoxelMaterial::Floor) return;
        ++floorVoxels;
        const double z = m.cubeOrigin.z + (c.z + 0.5) * m.voxelSize();
        EXPECT_GT(z, -0.5);
        EXPECT_LT(z, -0.4375);
    });
    EXPECT_EQ(floorVoxels, floor.voxels().size());
    // Seen from below, the floor hides the sphere: floor colour only.
    RenderSettings s;
    s.ambient = 1.0f;
    s.diffuse = 0.0f;
    const Camera cam = makeCamera({0, 0, -5}, {0, 0, 0}, {0, 1, 0}, 20, 41, 41);
    Frame fr;
    render("full", m, cam, fr, s);
    const std::size_t centre = fr.pixel(20, 20);
    ASSERT_NE(fr.hitId[centre], kNoHit);
    EXPECT_EQ(m.material(fr.hitId[centre]), VoxelMaterial::Floor);
    EXPECT_EQ(vec3(fr.rgba[centre]), s.floorColour);
}

TEST(MergeShells, OfAnOctreeWithAnEmptyOneDrawsTheSameImageAsTheOctree) {
    const Octree& t = sphereTree();
    Octree empty = t.emptyCopy();
    empty.setTopology(std::vector<OctreeNode>(1), {});
    const Octree m = mergeShells(t, empty);
    EXPECT_EQ(m.voxels().size(), t.voxels().size());
    const Camera cam = Camera::framing(cubeOf(t), 64, 48);
    Frame a, b;
    render("full", t, cam, a);
    render("full", m, cam, b);
    EXPECT_EQ(a.rgba.size(), b.rgba.size());
    for (std::size_t i = 0; i < a.rgba.size(); ++i) ASSERT_EQ(a.rgba[i], b.rgba[i]) << i;
}
