// Baked lighting: lit, shadowed and occluded voxels of analytic shells, the light parser.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/lighting/Bake.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

using namespace octrace;

namespace {
Octree sphereShell() { return buildShellOctree(makeAnalyticField("sphere", 33), {6, 0.0, 0}); }

/// Baked value of the voxel on the sphere (radius 0.7) in direction d from the centre.
int bakedAt(const Octree& t, const dvec3& d) {
    const dvec3 p = 0.7 * glm::normalize(d);
    const ivec3 cell = ivec3(glm::floor((p - t.cubeOrigin) / t.voxelSize()));
    for (int r = 0; r <= 2; ++r)  // the nearest boundary voxel around that point
        for (int x = -r; x <= r; ++x)
            for (int y = -r; y <= r; ++y)
                for (int z = -r; z <= r; ++z) {
                    const std::uint32_t v = t.findVoxel(cell + ivec3(x, y, z));
                    if (v != 0xFFFFFFFFu) return t.baked()[v];
                }
    ADD_FAILURE() << "no voxel near " << p.x << "," << p.y << "," << p.z;
    return -1;
}
}  // namespace

TEST(Bake, LightsTheSideFacingTheLightAndShadowsTheOther) {
    Octree t = sphereShell();
    BakeOptions o;
    o.lights = {parseBakeLight("dir:0,0,1")};
    o.aoRays = 0;
    BakeReport rep;
    bakeLighting(t, o, &rep);
    ASSERT_EQ(t.baked().size(), t.voxels().size());
    EXPECT_GT(rep.rays, t.voxels().size() / 2);
    EXPECT_GE(bakedAt(t, {0, 0, 1}), 250);                  // ambient + diffuse, facing the light
    EXPECT_LE(bakedAt(t, {0, 0, -1}), 39);                  // two-sided |n.l| = 1, but in the sphere's shadow
    EXPECT_NEAR(bakedAt(t, {1, 0, 1}), 255 * (0.15 + 0.85 * std::sqrt(0.5)), 12);
    // Without shadows the far side is lit as brightly (two-sided, as the dynamic shading).
    o.shadows = false;
    bakeLighting(t, o);
    EXPECT_GE(bakedAt(t, {0, 0, -1}), 250);
}

TEST(Bake, AmbientOcclusionDarkensTheTorusHoleAndOnlyShellsAreBaked) {
    // The torus (tube 0.25 around the circle of radius 0.6): the wall of its hole sees the
    // opposite wall 0.7 away, its outer rim sees nothing.
    Octree t = buildShellOctree(makeAnalyticField("torus", 33), {6, 0.0, 0});
    BakeOptions o;
    o.lights = {};
    o.aoRays = 16;
    o.ambient = 1.0f;
    o.aoDistance = 1.0;
    bakeLighting(t, o);
    int open = 0, inner = 0;
    auto at = [&](dvec3 p) {
        const std::uint32_t v = t.findVoxel(ivec3(glm::floor((p - t.cubeOrigin) / t.voxelSize())));
        return v == 0xFFFFFFFFu ? -1 : int(t.baked()[v]);
    };
    for (double d = 0.22; d <= 0.28 && (open <= 0 || inner <= 0); d += 0.005) {
        open = std::max(open, at({0.6 + d, 0.0, 0.0}));
        inner = std::max(inner, at({0.6 - d, 0.0, 0.0}));
    }
    ASSERT_GT(open, 0);
    ASSERT_GT(inner, 0);
    EXPECT_GT(open, inner);
    EXPECT_THROW(bakeLighting(t = [] {
        BuildOptions b{4, 0.0, 0};
        b.form = OctreeForm::Volume;
        return buildOctree(makeAnalyticField("sphere", 17), b);
    }(), o), UsageError);
}

TEST(Bake, DoesNotDependOnTheThreadsAndShadesRenderersByIt) {
    Octree a = sphereShell(), b = sphereShell();
    BakeOptions o;
    o.threads = 1;
    bakeLighting(a, o);
    o.threads = 0;
    bakeLighting(b, o);
    EXPECT_EQ(a.baked(), b.baked());
    // The shader uses the baked value when told to, the normal otherwise.
    Camera cam = Camera::framing(a.occupiedBounds(), 64, 48, 30.0);
    RenderSettings rs;
    const Shader baked(a, cam, rs);
    rs.baked = false;
    const Shader dynamic(a, cam, rs);
    int differ = 0;
    a.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        const vec4 x = baked.shade(v, c);
        EXPECT_NEAR(x.r, rs.colour.r * a.baked()[v] / 255.0f, 1e-6f);
        differ += x != dynamic.shade(v, c);
    });
    EXPECT_GT(differ, 0);
}

TEST(Bake, ParsesLights) {
    const BakeLight d = parseBakeLight("dir:0,0,2");
    EXPECT_FALSE(d.point);
    EXPECT_EQ(d.v, dvec3(0, 0, 1));
    const BakeLight p = parseBakeLight("point:1,2,3,0.5");
    EXPECT_TRUE(p.point);
    EXPECT_EQ(p.v, dvec3(1, 2, 3));
    EXPECT_FLOAT_EQ(p.intensity, 0.5f);
    for (const char* bad : {"dir:0,0,0", "sun:1,1,1", "dir:1,1", "point:1,2,3,-1", "dir:1,x,1", "point:1,2,3,4,5"})
        EXPECT_THROW(parseBakeLight(bad), UsageError) << bad;
}
