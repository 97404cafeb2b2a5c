// Display windows (radiology's window level / width): the grey of a value, the voxel values
// the build records under the surface for them, the albedo they give; and the voxel aspect of
// anisotropic grids (spacing is a world transform: the octree's cube stays cubic in world units).
#include "octrace/build/CtPresets.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/Shading.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;

namespace {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

/// v = world x on [0,1]^3, 17 samples an edge.
ScalarField rampX() {
    ScalarField f;
    f.name = "ramp";
    f.dims = ivec3(17);
    f.spacing = dvec3(1.0 / 16.0);
    f.values.resize(f.sampleCount());
    for (int k = 0; k < 17; ++k)
        for (int j = 0; j < 17; ++j)
            for (int i = 0; i < 17; ++i) f.values[f.index(i, j, k)] = float(i) / 16.0f;
    return f;
}

}  // namespace

TEST(ValueWindow, MapsCentreMinusHalfWidthToBlackAndCentrePlusHalfWidthToWhite) {
    const ValueWindow w{40.0, 400.0};
    EXPECT_EQ(w.grey(-160.0f, false), 0.0f);
    EXPECT_EQ(w.grey(240.0f, false), 1.0f);
    EXPECT_FLOAT_EQ(w.grey(40.0f, false), 0.5f);
    EXPECT_FLOAT_EQ(w.grey(140.0f, false), 0.75f);
    EXPECT_EQ(w.grey(-1000.0f, false), 0.0f);  // clamped
    EXPECT_EQ(w.grey(3000.0f, false), 1.0f);
    // MONOCHROME1: low values bright.
    EXPECT_EQ(w.grey(-160.0f, true), 1.0f);
    EXPECT_FLOAT_EQ(w.grey(140.0f, true), 0.25f);
    EXPECT_FALSE(ValueWindow{}.valid());
}

TEST(CtPresets, NameTheDocumentedHounsfieldValues) {
    EXPECT_EQ(ctIsoPreset("skin"), -500.0);
    EXPECT_EQ(ctIsoPreset("bone"), 300.0);
    EXPECT_FALSE(ctIsoPreset("300"));
    EXPECT_EQ(ctWindowPreset("lung")->centre, -600.0);
    EXPECT_EQ(ctWindowPreset("lung")->width, 1500.0);
    EXPECT_EQ(ctWindowPreset("brain")->width, 80.0);
    EXPECT_EQ(ctWindowPreset("soft-tissue")->centre, 40.0);
    EXPECT_EQ(ctWindowPreset("bone")->centre, 400.0);
    EXPECT_FALSE(ctWindowPreset("none"));
}

// On v = x the value one voxel edge inside the surface (towards v >= iso, against the normal)
// is the voxel centre's x plus one voxel edge: trilinear interpolation of a linear field is exact.
TEST(OctreeBuilder, RecordsTheValueOneVoxelInsideTheSurfaceWhenAsked) {
    const ScalarField f = rampX();
    BuildOptions o{4, 0.3, 1};
    EXPECT_TRUE(buildShellOctree(f, o).voxelValues().empty());
    o.voxelValues = true;
    const Octree t = buildShellOctree(f, o);
    ASSERT_EQ(t.voxelValues().size(), t.voxels().size());
    ASSERT_GT(t.voxels().size(), 0u);
    const double h = t.voxelSize();
    t.forEachVoxel([&](const ivec3& c, std::uint32_t i) {
        const double centreX = t.cubeOrigin.x + (c.x + 0.5) * h;
        EXPECT_NEAR(t.voxelValues()[i], centreX + h, 1e-6) << c.x << "," << c.y << "," << c.z;
    });
    EXPECT_NO_THROW(t.validate());
    // The same values whatever the threads.
    o.threads = 3;
    EXPECT_TRUE(buildShellOctree(f, o).voxelValues() == t.voxelValues());
}

TEST(Albedo, GreysEachVoxelByTheWindowOfItsValueAndFallsBackWithoutValues) {
    const ScalarField f = rampX();
    BuildOptions o{4, 0.3, 1};
    o.voxelValues = true;
    Octree t = buildShellOctree(f, o);
    RenderSettings rs;
    rs.window = {0.3, 0.4};
    const Albedo grey(t, rs);
    rs.invertedGrey = true;
    const Albedo inverted(t, rs);
    for (std::uint32_t i = 0; i < t.voxels().size(); ++i) {
        const float g = rs.window.grey(t.voxelValues()[i], false);
        EXPECT_EQ(grey.at(i, 0.0f), vec3(srgbToLinear(g)));
        EXPECT_EQ(inverted.at(i, 0.0f), vec3(srgbToLinear(1.0f - g)));
    }
    // Without voxel values (an octree file) or without a window: the uniform colour.
    rs.invertedGrey = false;
    rs.window = {};
    EXPECT_EQ(Albedo(t, rs).at(0, 0.0f), rs.colour);
    rs.window = {0.3, 0.4};
    t.setVoxelValues({});
    EXPECT_EQ(Albedo(t, rs).at(0, 0.0f), rs.colour);
}

// A sphere of radius 10 sampled every 0.5 x 0.5 x 2 units (a CT's thick slices) is a sphere
// in the octree too: its occupied box spans 20 units along each axis, to a voxel or two.
TEST(OctreeBuilder, AnisotropicSpacingIsAWorldTransformTheSurfaceKeepsItsShape) {
    ScalarField f;
    f.dims = ivec3(65, 65, 17);
    f.spacing = dvec3(0.5, 0.5, 2.0);
    f.origin = dvec3(-16.0, -16.0, -16.0);
    f.values.resize(f.sampleCount());
    for (int k = 0; k < f.dims.z; ++k)
        for (int j = 0; j < f.dims.y; ++j)
            for (int i = 0; i < f.dims.x; ++i) f.values[f.index(i, j, k)] = float(glm::length(f.worldFromGrid(i, j, k)));
    const Octree t = buildShellOctree(f, {7, 10.0, 0});
    EXPECT_DOUBLE_EQ(t.cubeSide, 32.0);
    const Box3 b = t.occupiedBounds();
    const double h = t.voxelSize();
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(b.hi[a] - b.lo[a], 20.0, 2.0 * h) << "axis " << a;
        EXPECT_NEAR(b.hi[a] + b.lo[a], 0.0, 2.0 * h) << "axis " << a;
    }
}
