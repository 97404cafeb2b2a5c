// The tile renderer (docs/dev/tile-renderer.md) is exact: for every scene of the renderer tests,
// at cameras in general position, on the lattice, inside the cube, grazing and orthographic, for
// several tile sizes and thread counts, its frame equals `full`'s bit for bit and its hits are
// the reference's; and on a scene built to defeat a conservative bound that ignores the ray's
// quantization (a wall one voxel thick just beside a tile's last column of rays), the widened
// pre-pass still sees what `full` sees while the unwidened one does not.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/Renderer.h"
#include "render/traversal/TileFrontier.h"
#include "render/traversal/TileRenderer.h"
#include "RenderTestUtil.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

using namespace octrace;
using namespace octrace::test;

namespace {

std::vector<NamedTree> smoothTrees() {
    static const Octree sphere = smoothTree("sphere", 33, 7), noise = smoothTree("noise", 65, 8, 7), rods = buildRods(true);
    return {{"smooth sphere", &sphere}, {"smooth noise", &noise}, {"smooth rods", &rods}};
}

RenderStats draw(const Renderer& r, const Octree& t, const Camera& c, Frame& f, int threads, int tile = 8,
                 SurfaceMode surface = SurfaceMode::Voxel) {
    RenderSettings s;
    s.surface = surface;
    s.threads = threads;
    s.tileSize = tile;
    return r.render(t, c, s, f);
}

}  // namespace

/// tile's frame `tf` (stats `ts`) equals full's `ff` (`fs`) bit for bit, its hits equal the
/// reference's `rf`, and it counts the same rays and hits.
static void expectSameAsFullAndReference(const Frame& tf, const RenderStats& ts, const Frame& ff, const RenderStats& fs,
                                  const Frame& rf) {
    const FrameDiff toFull = diffFrames(tf, ff);
    EXPECT_TRUE(toFull.identical()) << toFull.first;
    std::size_t offReference = 0;
    for (std::size_t i = 0; i < tf.hitId.size(); ++i) offReference += tf.hitId[i] != rf.hitId[i];
    EXPECT_EQ(offReference, 0u);
    EXPECT_EQ(ts.rays, fs.rays);
    EXPECT_EQ(ts.hits, fs.hits);
}

TEST(TileRenderer, EqualsFullBitForBitAndTheReferenceVoxelForVoxelOnEveryScene) {
    const auto full = makeRenderer("full"), tile = makeRenderer("tile"), reference = makeRenderer("reference");
    long hits = 0, startedBelowRoot = 0;
    for (const NamedTree& nt : hardTestTrees())
        for (const NamedCamera& nc : hardTestCameras(*nt.tree)) {
            Frame ff, rf;
            const RenderStats fs = draw(*full, *nt.tree, nc.camera, ff, 2);
            draw(*reference, *nt.tree, nc.camera, rf, 2);
            for (int tileSize : {1, 3, 8, 16}) {
                for (int threads : {1, 2, 7}) {
                    SCOPED_TRACE(nt.name + ", " + nc.name + ", tile " + std::to_string(tileSize) + ", threads " +
                                 std::to_string(threads));
                    Frame tf;
                    const RenderStats ts = draw(*tile, *nt.tree, nc.camera, tf, threads, tileSize);
                    expectSameAsFullAndReference(tf, ts, ff, fs, rf);
                    EXPECT_EQ(ts.pixels, fs.pixels);
                    EXPECT_EQ(ts.raysFull + ts.raysCommonPath, ts.pixels);
                    hits += long(ts.hits);
                    startedBelowRoot += long(ts.raysCommonPath);
                }
            }
        }
    EXPECT_GT(hits, 0);
    EXPECT_GT(startedBelowRoot, 0);
}

// Smooth surfaces: the interpolant's test runs inside tile's traversal from the frontier (full
// proposes the first boundary voxel and starts over from the root when it is passed); the
// boundary voxels are tested in the same order, so the frames are equal bit for bit.
TEST(TileRenderer, InSmoothModeEqualsFullBitForBitAndTheSmoothReferenceVoxelForVoxel) {
    const auto full = makeRenderer("full"), tile = makeRenderer("tile"), reference = makeRenderer("reference");
    long smoothHits = 0, passedVoxels = 0;
    for (const NamedTree& nt : smoothTrees()) {
        ASSERT_FALSE(nt.tree->corners().empty());
        for (const NamedCamera& nc : hardTestCameras(*nt.tree)) {
            Frame ff, rf, vf;
            const RenderStats fs = draw(*full, *nt.tree, nc.camera, ff, 2, 8, SurfaceMode::Smooth);
            draw(*reference, *nt.tree, nc.camera, rf, 2, 8, SurfaceMode::Smooth);
            draw(*full, *nt.tree, nc.camera, vf, 2, 8, SurfaceMode::Voxel);
            for (std::size_t i = 0; i < ff.hitId.size(); ++i) passedVoxels += vf.hitId[i] != kNoHit && ff.hitId[i] != vf.hitId[i];
            for (int tileSize : {1, 8, 16}) {
                for (int threads : {1, 2}) {
                    SCOPED_TRACE(nt.name + ", " + nc.name + ", tile " + std::to_string(tileSize) + ", threads " +
                                 std::to_string(threads));
                    Frame tf;
                    const RenderStats ts = draw(*tile, *nt.tree, nc.camera, tf, threads, tileSize, SurfaceMode::Smooth);
                    expectSameAsFullAndReference(tf, ts, ff, fs, rf);
                    smoothHits += long(ts.hits);
                }
            }
        }
    }
    EXPECT_GT(smoothHits, 0);
    EXPECT_GT(passedVoxels, 0);  // rays that pass a boundary voxel the interpolant misses: the case that matters
}

TEST(TileRenderer, VisitsFewerNodesThanFullOnTheFramedSurface) {
    const Octree& t = noiseTree();
    const Camera cam = Camera::framing(t.occupiedBounds(), 160, 120);
    Frame a, b;
    const RenderStats fs = draw(*makeRenderer("full"), t, cam, a, 2);
    const RenderStats ts = draw(*makeRenderer("tile"), t, cam, b, 2);
    EXPECT_TRUE(diffFrames(a, b).identical());
    EXPECT_LT(ts.nodesVisited, fs.nodesVisited);
}

/// RenderSettings::cancel: a render asked to stop before it starts draws no band of background
/// rows and no tile group; with
/// the flag present but false, the frame is the one drawn without it.
TEST(TileRenderer, StopsWhenCancelledAndDrawsTheSameFrameWhenNot) {
    const Octree& t = noiseTree();
    const Camera cam = Camera::framing(t.occupiedBounds(), 160, 120);
    const auto tile = makeRenderer("tile");
    Frame plain, flagged, stopped;
    RenderSettings s;
    s.threads = 2;
    const RenderStats ps = tile->render(t, cam, s, plain);
    std::atomic<bool> cancel{false};
    s.cancel = &cancel;
    tile->render(t, cam, s, flagged);
    EXPECT_TRUE(diffFrames(plain, flagged).identical());
    EXPECT_EQ(ps.pixels, std::uint64_t(160 * 120));
    cancel = true;
    const RenderStats ss = tile->render(t, cam, s, stopped);
    EXPECT_EQ(ss.pixels, 0u);
    EXPECT_EQ(ss.rays, 0u);
}

/// A wall one voxel thick (depth 7, the voxels [X, X + v) with X the cube's middle plane
/// x = 0) seen edge-on by an orthographic camera whose pixel column 31 has its exact ray a
/// quarter of the fixed point's unit (2^-14 lattice units) left of the wall: the ray misses
/// the wall, its quantized twin is rounded onto x = X and visits it. Column 31 is the last of
/// its 8-pixel tile, so the tile's exact frustum stops short of every node holding the wall.
TEST(TileRenderer, SeesAWallThatOnlyTheQuantizedRayOfATilesLastColumnMeets) {
    const double v = 2.0 / 128;
    const Octree t = buildShellOctree(sampleFunction("wall", ivec3(129), dvec3(-1.0), dvec3(v), [v](const dvec3& p) {
                                          return float(std::min(p.x + 20.0 * v, 0.5 * v - p.x));  // boundary at x in [0, v)
                                      }),
                                      {7, 0.0, 0});
    ASSERT_EQ(t.cubeSide, 2.0);  // octree units per world unit: 2^13, a power of two, so the rays below are exact
    const double eyeX = 1.0 / 64 - std::ldexp(1.0, -27);  // column 31's origin: x = -2^-27 world = -2^-14 lattice
    Camera cam = makeCamera({eyeX, 0.0, 3.0}, {eyeX, 0.0, 0.0}, {0, 1, 0}, 30, 64, 64);
    cam.projection = Camera::Projection::Orthographic;
    cam.orthoHeight = 2.0;
    Frame ff, tf, unwidened;
    draw(*makeRenderer("full"), t, cam, ff, 2);
    long wall = 0;
    for (int y = 0; y < 64; ++y) wall += ff.hitId[ff.pixel(31, y)] != kNoHit;
    ASSERT_GT(wall, 32) << "the scene does not put the wall on column 31's quantized rays";
    for (int tileSize : {8, 4, 2, 1}) {
        SCOPED_TRACE("tile " + std::to_string(tileSize));
        draw(*makeRenderer("tile"), t, cam, tf, 2, tileSize);
        const FrameDiff d = diffFrames(tf, ff);
        EXPECT_TRUE(d.identical()) << d.first;
    }
    // Without the widening the pre-pass culls the wall's nodes for the tile of columns 24-31.
    draw(detail::TileRenderer(false), t, cam, unwidened, 2);
    long lost = 0;
    for (int y = 0; y < 64; ++y) lost += unwidened.hitId[unwidened.pixel(31, y)] != ff.hitId[ff.pixel(31, y)];
    EXPECT_EQ(lost, wall);
}

// The frontier's frustum test of a node's eight children at once (AVX-512 where the processor
// has it) gives each child's own test bit for bit: random frusta (one with a NaN gradient, which
// the test passes), random nodes of every level, many of them straddling a plane.
TEST(TileFrontier, EightChildrenTestedAtOnceGiveEachChildsOwnTest) {
#if defined(__x86_64__) && defined(__GNUC__)
    if (!__builtin_cpu_supports("avx512f")) GTEST_SKIP() << "no AVX-512 F: both are the scalar code on this processor";
#endif
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double L = std::ldexp(1.0, Octree::kIntBits);
    std::size_t mixed = 0, nodes = 0;
    for (int k = 0; k < 300; ++k) {
        detail::TileFrustum f;
        f.apex = dvec3(0.5 + 1.5 * u(rng), 0.5 + 1.5 * u(rng), 0.5 + 1.5 * u(rng)) * L;
        for (dvec3& g : f.g) g = dvec3(u(rng), u(rng), u(rng));
        for (double& h : f.h) h = rng() % 2 ? 0.0 : 0.1 * L * u(rng);
        f.pad = rng() % 2 ? 0.0 : 1e-3;
        if (k == 0) f.g[2].y = std::numeric_limits<double>::quiet_NaN();
        f.prepare();
        for (int n = 0; n < 300; ++n) {
            const int level = int(rng() % unsigned(Octree::kIntBits));  // the children's level is at most kIntBits
            const unsigned span = 1u << level;
            const ivec3 cell(int(rng() % span), int(rng() % span), int(rng() % span));
            unsigned each = 0;
            for (unsigned c = 0; c < 8; ++c)
                if (f.meets(cell * 2 + ivec3(int(c >> 2), int((c >> 1) & 1), int(c & 1)), level + 1)) each |= 1u << c;
            ASSERT_EQ(f.meetsChildren(cell, level), each) << "level " << level;
            mixed += each != 0 && each != 0xFF;
            ++nodes;
        }
    }
    EXPECT_GT(mixed, nodes / 100);
}

// A node's pixel rectangle is the same whether its corners are projected eight at once
// (AVX-512) or one by one: every node of every test scene, at every test camera (inside the
// cube, grazing, orthographic), so that both the projected rectangles and the fallback to every
// pixel (a corner behind a perspective eye) occur.
TEST(TileFrontier, PixelRectanglesAreTheSameProjectedAtOnceOrCornerByCorner) {
#if defined(__x86_64__) && defined(__GNUC__)
    if (!__builtin_cpu_supports("avx512f")) GTEST_SKIP() << "no AVX-512 F: both are the scalar code on this processor";
#endif
    std::size_t projected = 0, everyPixel = 0;
    for (const NamedTree& nt : hardTestTrees())
        for (const NamedCamera& nc : hardTestCameras(*nt.tree)) {
            SCOPED_TRACE(nt.name + ", " + nc.name);
            const Octree& t = *nt.tree;
            const Camera& cam = nc.camera;
            const RayGenerator gen(cam);
            const detail::PixelRays rays(t, cam);
            const detail::ScreenSlopes slopes(t, gen, rays, cam.width, cam.height, true);
            const detail::TileFrustum f = detail::tileFrustum(gen, slopes, 0, 0, cam.width, cam.height);
            std::function<void(const StartNode&)> visit = [&](const StartNode& s) {
                detail::FrontierNode a{s}, b{s};
                detail::pixelRect(t, gen, f, a, cam.width, cam.height, false);
                detail::pixelRect(t, gen, f, b, cam.width, cam.height, true);
                ASSERT_EQ(a.projected, b.projected);
                ASSERT_EQ(a.x0, b.x0);
                ASSERT_EQ(a.x1, b.x1);
                ASSERT_EQ(a.y0, b.y0);
                ASSERT_EQ(a.y1, b.y1);
                ++(a.projected ? projected : everyPixel);
                const OctreeNode& nd = t.nodes()[s.node];
                if (s.level + 1 >= t.depth) return;
                for (unsigned c = 0; c < 8; ++c)
                    if ((nd.childMask >> c & 1u) && !(nd.termMask >> c & 1u))
                        visit({nd.firstChild + childRank(nd.childMask, c), s.level + 1,
                               s.cell * 2 + ivec3(int(c >> 2), int((c >> 1) & 1), int(c & 1))});
            };
            if (!t.nodes().empty()) visit(StartNode{});
        }
    EXPECT_GT(projected, 1000u);
    EXPECT_GT(everyPixel, 10u);
}
