// Smooth surfaces (render/SmoothSurface.h): the corner codes, the fast renderers against the
// smooth reference (its own float64 march) on several scenes and cameras, and the surface they
// find against the analytic one.
#include "RenderTestUtil.h"

#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/Renderer.h"
#include "octrace/render/SmoothSurface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <random>

using namespace octrace;
using namespace octrace::test;

namespace {


const Octree& smoothSphere() {
    static const Octree t = smoothTree("sphere", 33, 7);
    return t;
}
const Octree& smoothTorus() {
    static const Octree t = smoothTree("torus", 33, 6);
    return t;
}
const Octree& smoothNoise() {
    static const Octree t = smoothTree("noise", 65, 8, 7);
    return t;
}

/// The tree's voxels that have corner values (cell, voxel index), in the tree's order.
std::vector<std::pair<ivec3, std::uint32_t>> voxelsWithCorners(const Octree& tree) {
    std::vector<std::pair<ivec3, std::uint32_t>> out;
    tree.forEachVoxel([&](const ivec3& cell, std::uint32_t v) {
        if (tree.corners()[v] != 0) out.emplace_back(cell, v);
    });
    return out;
}

RenderSettings smoothSettings() {
    RenderSettings s;
    s.surface = SurfaceMode::Smooth;
    return s;
}

// The exact fast ray casters: every voxel renderer that traces rays but the references (the
// unquantized one traces another line) and the approximate linear and area (miss coherence and
// the start at the branch node change pixels by design, smooth or not: coherence.md).
std::vector<std::string> fastRayCasters() {
    std::vector<std::string> out;
    for (const std::string& n : rendererNames()) {
        const auto r = makeRenderer(n);
        if (r->drawsVoxels() && r->tracesRays() && !r->missCoherence() && n.rfind("reference", 0) != 0) out.push_back(n);
    }
    return out;
}

}  // namespace

TEST(SmoothSurface, CornerCodesKeepEachCornersSideAndTheRatios) {
    const float v[8] = {-3.0f, 1.0f, 0.001f, -0.0001f, 0.0f, 2.5f, -1.5f, 3.0f};
    double d[8];
    decodeCorners(encodeCorners(v, 0.0f), d);
    for (int q = 0; q < 8; ++q) {
        EXPECT_EQ(d[q] >= 0.0, v[q] >= 0.0f) << "corner " << q;
        // Half a step of rounding; a step where a corner just below the iso value is kept below.
        EXPECT_NEAR(d[q], v[q] / 3.0, (v[q] < 0.0f && v[q] > -1.5f / 127.0f * 3.0f ? 1.0 : 0.5) / 127.0 + 1e-12) << "corner " << q;
    }
    // Scale-free: the same field times 1000 and shifted by the iso value codes alike.
    float w[8];
    for (int q = 0; q < 8; ++q) w[q] = v[q] * 1000.0f + 20.0f;
    EXPECT_EQ(encodeCorners(v, 0.0f), encodeCorners(w, 20.0f));
    const float flat[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    EXPECT_EQ(encodeCorners(flat, 1.0f), 0u);
}

TEST(SmoothSurface, FastRenderersFindTheReferencesCellAndDepth) {
    // Same hit cell per pixel as the smooth reference, depth within 1e-3 of a voxel.
    const std::pair<std::string, const Octree*> trees[] = {
        {"sphere", &smoothSphere()}, {"torus", &smoothTorus()}, {"noise", &smoothNoise()}};
    const RenderSettings s = smoothSettings();
    for (const auto& [treeName, tree] : trees) {
        ASSERT_FALSE(tree->corners().empty());
        const double tolerance = 1e-3 * tree->voxelSize();
        for (const NamedCamera& nc : allTestCameras(*tree)) {
            Frame ref;
            render("reference", *tree, nc.camera, ref, s);
            for (const std::string& name : fastRayCasters()) {
                SCOPED_TRACE(treeName + ", camera " + nc.name + ", " + name);
                Frame f;
                render(name, *tree, nc.camera, f, s);
                std::size_t cells = 0, depths = 0, hits = 0;
                double worst = 0.0;
                for (std::size_t p = 0; p < f.hitId.size(); ++p) {
                    if (f.hitId[p] != ref.hitId[p]) {
                        ++cells;
                        continue;
                    }
                    if (f.hitId[p] == kNoHit) continue;
                    ++hits;
                    const double e = std::abs(double(f.depth[p]) - double(ref.depth[p]));
                    worst = std::max(worst, e);
                    if (!(e <= tolerance)) ++depths;
                }
                EXPECT_EQ(cells, 0u) << "pixels whose hit voxel differs from the reference's";
                EXPECT_EQ(depths, 0u) << "pixels whose depth differs by more than 1e-3 voxel; worst " << worst / tree->voxelSize()
                                      << " voxel";
                if (nc.name == "framing") {
                    EXPECT_GT(hits, f.hitId.size() / 20);  // not vacuous
                }
            }
        }
    }
}

TEST(SmoothSurface, ObjectOrderRenderersAgreeWithTheRayCasters) {
    // direct and direct-f2b test each voxel on its own (no side carried from the voxel before):
    // they may differ only where a crossing lies on a face shared by two boundary voxels.
    const RenderSettings s = smoothSettings();
    const Octree& tree = smoothSphere();
    const Camera cam = Camera::framing(cubeOf(tree), 120, 90);
    Frame full;
    render("full", tree, cam, full, s);
    for (const char* name : {"direct", "direct-f2b"}) {
        Frame f;
        render(name, tree, cam, f, s);
        std::size_t differ = 0;
        for (std::size_t p = 0; p < f.hitId.size(); ++p) differ += f.hitId[p] != full.hitId[p];
        EXPECT_LE(differ, f.hitId.size() / 200) << name;
    }
}

TEST(SmoothSurface, HitsLieOnTheAnalyticSphereFarCloserThanVoxelBoxes) {
    // The sphere field 0.7 - |p| on 33 samples over [-1,1]^3 (spacing 1/16), at depth 7 (voxel
    // 1/64): the smooth hit points lie on the interpolant, within a small part of a sample
    // spacing of the sphere; the voxel boxes' entry points lie up to a voxel diagonal off.
    const Octree& tree = smoothSphere();
    const Camera cam = makeCamera({2.1, -2.7, 1.6}, {0, 0, 0}, {0, 0, 1}, 30, 160, 120);
    const RayGenerator gen(cam);
    auto radiusErrors = [&](SurfaceMode mode) {
        RenderSettings s;
        s.surface = mode;
        Frame f;
        render("full", tree, cam, f, s);
        std::vector<double> e;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const std::size_t p = f.pixel(x, y);
                if (f.hitId[p] == kNoHit) continue;
                const dvec3 point = gen.origin(x, y) + double(f.depth[p]) * glm::normalize(gen.direction(x, y));
                e.push_back(std::abs(glm::length(point) - 0.7));
            }
        std::sort(e.begin(), e.end());
        return e;
    };
    const std::vector<double> smooth = radiusErrors(SurfaceMode::Smooth), voxel = radiusErrors(SurfaceMode::Voxel);
    ASSERT_GT(smooth.size(), 1000u);
    const double spacing = 2.0 / 32.0;
    const double p99Smooth = smooth[smooth.size() * 99 / 100], p99Voxel = voxel[voxel.size() * 99 / 100];
    EXPECT_LT(p99Smooth, 0.05 * spacing) << "voxel mode: " << p99Voxel;
    EXPECT_LT(p99Smooth * 5.0, p99Voxel);
}

TEST(SmoothSurface, VoxelModeAndOctreesWithoutCornersDrawBoxes) {
    // Without corners (or with surface = voxel) a frame is the voxel frame, bit for bit.
    const Octree& tree = smoothSphere();
    const Camera cam = Camera::framing(cubeOf(tree), 96, 72);
    Frame a, b, c;
    render("full", sphereTree(), cam, a, smoothSettings());  // the same field without corners
    render("full", sphereTree(), cam, b);
    render("full", tree, cam, c);  // corners, but surface = voxel
    EXPECT_TRUE(diffFrames(a, b).identical());
    EXPECT_TRUE(diffFrames(c, b).identical());
}

TEST(SmoothSurface, ColouringByHeightFollowsTheHitPointNotTheVoxel) {
    // Unlit (ambient 1, diffuse 0) and coloured by height with viridis, whose green grows with
    // its argument: a smooth hit's colour is the map's at the hit's own height, so green grows
    // with the hit points' height across the picture and varies inside a voxel's pixels (the
    // voxel's centre would give each voxel one colour and steps between them).
    const Octree& tree = smoothSphere();
    const Camera cam = makeCamera({2.1, -2.7, 1.6}, {0, 0, 0}, {0, 0, 1}, 30, 640, 480);  // a voxel ~5 pixels wide
    const RayGenerator gen(cam);
    RenderSettings s = smoothSettings();
    s.colormap = "viridis";
    s.ambient = 1.0f;
    s.diffuse = 0.0f;
    Frame f;
    render("full", tree, cam, f, s);
    std::vector<std::pair<double, float>> byHeight;  // (hit z, green)
    std::map<std::uint32_t, std::pair<float, float>> perVoxel;  // green's range in each voxel
    std::map<std::uint32_t, int> pixels;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const std::size_t p = f.pixel(x, y);
            if (f.hitId[p] == kNoHit) continue;
            const double z = (gen.origin(x, y) + double(f.depth[p]) * glm::normalize(gen.direction(x, y))).z;
            const float g = f.rgba[p].g;
            byHeight.emplace_back(z, g);
            ++pixels[f.hitId[p]];
            auto [it, fresh] = perVoxel.try_emplace(f.hitId[p], g, g);
            it->second.first = std::min(it->second.first, g);
            it->second.second = std::max(it->second.second, g);
        }
    ASSERT_GT(byHeight.size(), 1000u);
    std::sort(byHeight.begin(), byHeight.end());
    std::size_t descents = 0;
    for (std::size_t i = 1; i < byHeight.size(); ++i) descents += byHeight[i].second < byHeight[i - 1].second - 1e-5f;
    EXPECT_EQ(descents, 0u) << "green falls where the hit height rises";
    std::size_t varying = 0, seen = 0;  // of the voxels drawn in 4 pixels or more
    for (const auto& [voxel, range] : perVoxel) {
        if (pixels[voxel] < 4) continue;
        ++seen;
        varying += range.second > range.first;
    }
    ASSERT_GT(seen, 50u);
    EXPECT_GT(varying, seen * 3 / 4) << "voxels whose pixels show more than one colour, of " << seen << " drawn in 4 pixels or more";
}

TEST(SmoothSurface, RaysTestedTogetherGetEachRaysOwnTestBitForBit) {
    // testLanes (with AVX-512: the clip, the cubic and the search's first steps eight rays at a
    // time) against test() ray by ray: the result, every field of the hit and the carried side,
    // bit for bit, for 1 .. 16 rays through one voxel. Rays aim at random points of the voxel
    // (some just outside it, so that the clip fails), from eyes near and far, some parallel to
    // an axis or two (a zero direction component: clip's special case), carrying no side yet
    // or either side; some with a direction component so small that its inverse is infinite, some
    // parallel to an axis from exactly on the padded box's face.
#if defined(__x86_64__) && defined(__GNUC__)
    if (!__builtin_cpu_supports("avx512f")) GTEST_SKIP() << "no AVX-512: testLanes is test() ray by ray";
#else
    GTEST_SKIP() << "not x86: testLanes is test() ray by ray";
#endif
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int compared = 0, accepted = 0, refused = 0;
    for (const Octree* tree : {&smoothNoise(), &smoothSphere(), &smoothTorus()}) {
        const SmoothSurface surface(*tree, smoothSettings());
        ASSERT_TRUE(surface.active());
        const auto voxels = voxelsWithCorners(*tree);
        ASSERT_FALSE(voxels.empty());
        const double side = tree->voxelSize();
        for (int trial = 0; trial < 3000; ++trial) {
            const auto& [cell, voxel] = voxels[std::size_t(rng() % voxels.size())];
            const dvec3 lo = tree->cubeOrigin + dvec3(cell) * side;
            const unsigned count = 1 + unsigned(rng() % 16);
            std::vector<SmoothSurface::RayState> one(count), many(count);
            std::vector<TraversalHit> hitOne(count), hitMany(count);
            for (unsigned k = 0; k < count; ++k) {
                // A target in the voxel widened by a tenth on each side.
                const dvec3 target = lo + side * dvec3(unit(rng) * 1.2 - 0.1, unit(rng) * 1.2 - 0.1, unit(rng) * 1.2 - 0.1);
                dvec3 dir(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
                const unsigned kind = unsigned(rng() % 8);
                if (kind == 0) dir.x = 0.0;
                if (kind == 1) dir.y = dir.z = 0.0;
                if (kind == 2) dir.z = -0.0;
                dir = glm::normalize(dir);
                if (kind == 5) dir.y = 1e-310;  // 1 / 1e-310 overflows: the slab's times are infinite or NaN
                // The eye: far off, a voxel or two off, or inside the voxel.
                const double back = kind == 3 ? side * 0.3 : kind == 4 ? side * 1.5 : side * (2.0 + 500.0 * unit(rng));
                Ray r{target - back * dir, dir};
                if (kind == 5 && rng() % 2) r.origin.y = lo.y - 1e-7 * side;  // on the slab's plane: 0 x inf, NaN
                if (kind == 6) {
                    // Parallel to z from exactly on the padded box's face at x = lo.x - pad (clip's
                    // own arithmetic), or on the far face.
                    r.direction = dvec3(0.0, 0.0, unit(rng) < 0.5 ? 1.0 : -1.0);
                    const double pad = 1e-7 * side;
                    r.origin = dvec3(rng() % 2 ? lo.x - pad : lo.x + side + pad, target.y, target.z - 3.0 * side * r.direction.z);
                }
                one[k] = SmoothSurface::RayState(r);
                one[k].side = int(rng() % 3) - 1;
                many[k] = one[k];
                TraversalHit h;
                h.voxel = voxel;
                h.cell = cell;
                hitOne[k] = hitMany[k] = h;
            }
            std::vector<SmoothSurface::RayState*> states(count);
            std::vector<TraversalHit*> hits(count);
            for (unsigned k = 0; k < count; ++k) {
                states[k] = &many[k];
                hits[k] = &hitMany[k];
            }
            const unsigned got = surface.testLanes(states.data(), hits.data(), count);
            for (unsigned k = 0; k < count; ++k) {
                const int sideBefore = one[k].side;
                const bool want = surface.test(one[k], hitOne[k]);
                const std::string what = "trial " + std::to_string(trial) + " ray " + std::to_string(k) + " of " +
                                         std::to_string(count) + ", side before " + std::to_string(sideBefore);
                ASSERT_EQ(bool(got >> k & 1u), want) << what;
                ASSERT_EQ(many[k].side, one[k].side) << what;
                ASSERT_EQ(hitMany[k].smooth, hitOne[k].smooth) << what;
                ASSERT_EQ(std::bit_cast<std::uint64_t>(hitMany[k].distance), std::bit_cast<std::uint64_t>(hitOne[k].distance)) << what;
                for (int a = 0; a < 3; ++a)
                    ASSERT_EQ(std::bit_cast<std::uint32_t>(hitMany[k].normal[a]), std::bit_cast<std::uint32_t>(hitOne[k].normal[a])) << what;
                ASSERT_EQ(std::bit_cast<std::uint32_t>(hitMany[k].zCells), std::bit_cast<std::uint32_t>(hitOne[k].zCells)) << what;
                ++compared;
                ++(want ? accepted : refused);
            }
        }
    }
    // Every outcome occurs often.
    EXPECT_GT(accepted, compared / 10);
    EXPECT_GT(refused, compared / 10);
    EXPECT_GT(compared, 40000);
}

TEST(SmoothSurface, TheFirstOfThreeCrossingsInOneVoxelIsFound) {
    // Along a voxel's diagonal the trilinear interpolant is the cubic whose Bernstein
    // coefficients are the corner values averaged by their number of upper coordinates (0, 1, 2,
    // 3). These corners give g(t) = 4 (t - 1/2)^3 - (t - 1/2) / 2: below at the entry, above at
    // the exit, crossing at t = 0.146, 0.5 and 0.854, its derivative positive at both ends and
    // negative between its extrema (t = 0.296, 0.704). The fast test must split the span at the
    // extrema and find the first crossing, as the reference's march does; searched over the
    // whole span at once (the end points alone on opposite sides), it found the middle one. Rays
    // near the diagonal in both directions, carrying no side yet, and through each half.
    const float b1 = -0.25f + 2.5f / 3.0f;  // g(0) + g'(0) / 3
    const float values[8] = {-0.25f, b1, b1, -b1, b1, -b1, -b1, 0.25f};  // corner q = 4x + 2y + z
    Octree tree = smoothSphere().copy();
    const auto voxels = voxelsWithCorners(tree);
    ASSERT_FALSE(voxels.empty());
    const auto [cell, voxel] = voxels[voxels.size() / 2];
    std::vector<std::uint64_t> corners = tree.corners();
    corners[voxel] = encodeCorners(values, 0.0f);
    tree.setCorners(std::move(corners));
    const SmoothSurface surface(tree, smoothSettings());
    ASSERT_TRUE(surface.active());
    const double side = tree.voxelSize();
    const dvec3 lo = tree.cubeOrigin + dvec3(cell) * side;
    for (int k = 0; k < 40; ++k) {
        // A point near the voxel's centre, a direction near the diagonal (forwards or backwards).
        const double e = 0.01 * (k % 5 - 2), f = 0.01 * (k / 10 - 1.5);  // 20 offsets, 40 distinct rays
        const bool backwards = k / 5 % 2 != 0;
        const dvec3 through = lo + side * dvec3(0.5 + e, 0.5 - e, 0.5 + f);
        const dvec3 dir = glm::normalize(dvec3(1.0, 1.0 + e, 1.0 - f) * (backwards ? -1.0 : 1.0));
        const Ray ray{through - 3.0 * side * dir, dir};
        SmoothSurface::RayState fast(ray), ref(ray);
        TraversalHit hitFast, hitRef;
        hitFast.voxel = hitRef.voxel = voxel;
        hitFast.cell = hitRef.cell = cell;
        ASSERT_TRUE(surface.testReference(ref, hitRef)) << "ray " << k;
        ASSERT_TRUE(surface.test(fast, hitFast)) << "ray " << k;
        // The first crossing: about 0.146 of the diagonal past the entry corner, when the ray
        // enters at the lower corner (forwards), about 0.146 past the upper one (backwards: g
        // mirrored is -g, and from the upper corner the first crossing is the same distance in).
        const double entry = glm::length(through - ray.origin) - 0.5 * std::sqrt(3.0) * side;
        EXPECT_NEAR((hitRef.distance - entry) / (std::sqrt(3.0) * side), 0.146, 0.03) << "ray " << k;
        EXPECT_NEAR(hitFast.distance, hitRef.distance, 1e-3 * side) << "ray " << k;
    }
}

TEST(SmoothSurface, TheNormalIsTheInterpolantsGradientAtTheHit) {
    // At each accepted hit the normal points against the gradient of the voxel's trilinear
    // interpolant at the hit point. The interpolant is linear along each axis, so a difference
    // across the point gives each partial derivative exactly (up to rounding): an independent
    // check of the gradient's formula, on voxels with random corner values (every corner term
    // of the interpolant present), rays in random directions.
    std::mt19937_64 rng(71);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Octree tree = smoothSphere().copy();
    const auto voxels = voxelsWithCorners(tree);
    ASSERT_GE(voxels.size(), 40u);
    std::vector<std::uint64_t> corners = tree.corners();
    for (std::size_t i = 0; i < 40; ++i) {
        float values[8];
        for (float& v : values) v = float(unit(rng) * 2.0 - 1.0);
        values[0] = -0.5f;  // both sides present
        values[7] = 0.5f;
        corners[voxels[i].second] = encodeCorners(values, 0.0f);
    }
    tree.setCorners(std::move(corners));
    const SmoothSurface surface(tree, smoothSettings());
    const double side = tree.voxelSize();
    int accepted = 0;
    for (std::size_t i = 0; i < 40; ++i) {
        const auto [cell, voxel] = voxels[i];
        double d[8];
        decodeCorners(tree.corners()[voxel], d);
        auto f = [&](const dvec3& p) {  // corner q = 4x + 2y + z
            double sum = 0.0;
            for (int q = 0; q < 8; ++q)
                sum += d[q] * ((q & 4) ? p.x : 1.0 - p.x) * ((q & 2) ? p.y : 1.0 - p.y) * ((q & 1) ? p.z : 1.0 - p.z);
            return sum;
        };
        const dvec3 lo = tree.cubeOrigin + dvec3(cell) * side;
        for (int k = 0; k < 50; ++k) {
            const dvec3 target = lo + side * dvec3(unit(rng), unit(rng), unit(rng));
            const dvec3 dir = glm::normalize(dvec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5));
            const Ray ray{target - 4.0 * side * dir, dir};
            SmoothSurface::RayState state(ray);
            TraversalHit hit;
            hit.voxel = voxel;
            hit.cell = cell;
            if (!surface.test(state, hit)) continue;
            const dvec3 p = (ray.origin + hit.distance * dir - lo) / side;
            const double h = 1e-3;
            const dvec3 g((f(p + dvec3(h, 0, 0)) - f(p - dvec3(h, 0, 0))) / (2 * h),
                          (f(p + dvec3(0, h, 0)) - f(p - dvec3(0, h, 0))) / (2 * h),
                          (f(p + dvec3(0, 0, h)) - f(p - dvec3(0, 0, h))) / (2 * h));
            if (!(glm::length(g) > 1e-3)) continue;  // a flat point: the direction is not defined
            const dvec3 want = -glm::normalize(g);
            for (int a = 0; a < 3; ++a) EXPECT_NEAR(hit.normal[a], want[a], 1e-5) << "voxel " << i << " ray " << k << " axis " << a;
            ++accepted;
        }
    }
    EXPECT_GT(accepted, 200);
}
