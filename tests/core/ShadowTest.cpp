// Shadow rays of the dynamic shading on voxel octrees (RenderSettings::shadows): a square slab
// above a floor, lit from straight above, casts its square on the floor and nowhere else, and
// every voxel renderer colours a voxel alike.
#include "RenderTestUtil.h"
#include "octrace/build/Volume.h"
#include "octrace/render/Shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace octrace;
using namespace octrace::test;

namespace {

constexpr double kHalf = 0.3;     // the slab: |x|, |y| < kHalf, 0.1 < z < 0.3
constexpr double kFloor = -0.5;   // the floor: z < kFloor

/// Positive inside the slab or the floor, 65 samples per axis over [-1,1]^3.
ScalarField slabOverFloor() {
    ScalarField f;
    f.name = "slab";
    f.dims = ivec3(65);
    f.origin = dvec3(-1.0);
    f.spacing = dvec3(2.0 / 64);
    for (int k = 0; k < 65; ++k)
        for (int j = 0; j < 65; ++j)
            for (int i = 0; i < 65; ++i) {
                const dvec3 p = f.origin + dvec3(i, j, k) * f.spacing;
                const double slab = std::min({kHalf - std::abs(p.x), kHalf - std::abs(p.y), 0.1 - std::abs(p.z - 0.2)});
                f.values.push_back(float(std::max(slab, kFloor - p.z)));
            }
    return f;
}

const Octree& slabTree() {
    static const Octree t = buildShellOctree(slabOverFloor(), {6, 0.0, 0});
    return t;
}

/// Low and to the south, so that the floor under the slab is in view.
Camera lowCamera() { return makeCamera({0.15, -2.6, 0.35}, {0.0, 0.0, -0.55}, {0, 0, 1}, 40, 120, 90); }

/// Dynamic shading with the light straight above (world +z), given in the camera's space.
RenderSettings lightFromAbove(const Camera& c, bool shadows) {
    dvec3 right, up, back;
    c.basis(right, up, back);
    const dvec3 l(0, 0, 1);
    RenderSettings s;
    s.lightCamera = dvec3(glm::dot(l, right), glm::dot(l, up), glm::dot(l, back));
    s.baked = false;
    s.shadows = shadows;
    return s;
}

std::vector<ivec3> cellsByVoxel(const Octree& t) {
    std::vector<ivec3> cells(t.voxels().size());
    t.forEachVoxel([&](const ivec3& c, std::uint32_t v) { cells[v] = c; });
    return cells;
}

bool sameColour(const vec4& a, const vec4& b) { return std::memcmp(&a, &b, sizeof(vec4)) == 0; }

}  // namespace

TEST(Shadows, DarkenTheFloorUnderTheSlabAndLeaveEveryOtherVoxelAsItWas) {
    const Octree& t = slabTree();
    const Camera cam = lowCamera();
    Frame on, off;
    const RenderStats son = render("full", t, cam, on, lightFromAbove(cam, true));
    const RenderStats soff = render("full", t, cam, off, lightFromAbove(cam, false));
    ASSERT_EQ(on.hitId, off.hitId);
    const std::vector<ivec3> cells = cellsByVoxel(t);
    const double h = t.voxelSize(), margin = 2.0 * h;
    const RenderSettings s = lightFromAbove(cam, true);
    const vec4 ambientOnly(s.colour * s.ambient, 1.0f);
    std::size_t shadowed = 0, lit = 0, slabTop = 0;
    for (std::size_t p = 0; p < on.hitId.size(); ++p) {
        if (on.hitId[p] == kNoHit) continue;
        const dvec3 c = t.cubeOrigin + (dvec3(cells[on.hitId[p]]) + 0.5) * h;
        const double ax = std::abs(c.x), ay = std::abs(c.y);
        if (c.z < kFloor + margin && c.z > kFloor - margin) {
            if (ax < kHalf - margin && ay < kHalf - margin) {
                ++shadowed;  // under the slab: the light's share is gone, the ambient stays
                EXPECT_TRUE(sameColour(on.rgba[p], ambientOnly)) << "pixel " << p << " at " << c.x << "," << c.y;
                EXPECT_LT(on.rgba[p].r, off.rgba[p].r);
            } else if (ax > kHalf + margin || ay > kHalf + margin) {
                ++lit;
                EXPECT_TRUE(sameColour(on.rgba[p], off.rgba[p])) << "pixel " << p << " at " << c.x << "," << c.y;
            }
        } else if (c.z > 0.3 - margin) {
            ++slabTop;
            EXPECT_TRUE(sameColour(on.rgba[p], off.rgba[p])) << "pixel " << p;
        }
    }
    EXPECT_GT(shadowed, 100u);
    EXPECT_GT(lit, 200u);
    EXPECT_GT(slabTop, 50u);
    // One shadow ray per lit pixel at least (a few step past the surface's own neighbours);
    // side faces (n . l = 0) trace none.
    EXPECT_GE(son.secondaryRays, shadowed + lit + slabTop);
    EXPECT_LE(son.secondaryRays, 4 * son.hits);
    EXPECT_EQ(soff.secondaryRays, 0u);
}

TEST(Shadows, EveryVoxelRendererColoursTheSameVoxelAlikeAndTheExactOnesGiveTheSameImage) {
    const Octree& t = slabTree();
    const Camera cam = lowCamera();
    const RenderSettings s = lightFromAbove(cam, true);
    Frame full;
    const RenderStats sfull = render("full", t, cam, full, s);
    for (const char* name : {"linear", "area", "linear-exact", "area-exact", "reference", "reference-unquantized", "direct", "direct-f2b"}) {
        SCOPED_TRACE(name);
        Frame f;
        const RenderStats st = render(name, t, cam, f, s);
        std::size_t same = 0;
        for (std::size_t p = 0; p < f.hitId.size(); ++p)
            if (f.hitId[p] != kNoHit && f.hitId[p] == full.hitId[p]) {
                ++same;
                EXPECT_TRUE(sameColour(f.rgba[p], full.rgba[p])) << "pixel " << p;
            }
        EXPECT_GT(same, full.hitId.size() / 3);
        const std::string n = name;
        if (n == "linear-exact" || n == "area-exact" || n == "reference") {
            const FrameDiff d = diffFrames(f, full);
            EXPECT_TRUE(d.identical()) << d.first;
            EXPECT_EQ(st.secondaryRays, sfull.secondaryRays);
        }
    }
}

TEST(Shadows, ImagesAndShadowRayCountsDoNotDependOnTheThreadCount) {
    const Octree& t = slabTree();
    const Camera cam = lowCamera();
    for (const char* name : {"full", "area", "direct"}) {
        SCOPED_TRACE(name);
        RenderSettings s = lightFromAbove(cam, true);
        s.threads = 1;
        Frame one;
        const RenderStats s1 = render(name, t, cam, one, s);
        for (int threads : {2, 7}) {
            s.threads = threads;
            Frame f;
            const RenderStats st = render(name, t, cam, f, s);
            const FrameDiff d = diffFrames(f, one);
            EXPECT_TRUE(d.identical()) << threads << " threads: " << d.first;
            EXPECT_EQ(st.secondaryRays, s1.secondaryRays) << threads << " threads";
        }
    }
}

TEST(Shadows, AreOffByDefaultOnVoxelOctreesAndNeverDarkenBakedLight) {
    Octree t = slabTree().copy();
    const Camera cam = lowCamera();
    RenderSettings s = lightFromAbove(cam, false);
    s.shadows.reset();
    EXPECT_FALSE(Shader(t, cam, s).shadows());
    s.shadows = true;
    EXPECT_TRUE(Shader(t, cam, s).shadows());
    t.setBaked(std::vector<std::uint8_t>(t.voxels().size(), 200));
    s.baked = true;
    EXPECT_FALSE(Shader(t, cam, s).shadows());
    Frame f;
    EXPECT_EQ(render("full", t, cam, f, s).secondaryRays, 0u);
}
