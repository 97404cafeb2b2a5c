// Multi-resolution: node summaries, and the level-of-detail cut shared by full, reference and
// the direct renderers.
#include "RenderTestUtil.h"

#include "octrace/render/Lod.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;
using namespace octrace::test;

namespace {

const Octree& summarized() {
    static const Octree t = [] {
        Octree o = buildShellOctree(makeAnalyticField("noise", 65, 7), {8, 0.0, 0});
        o.computeSummaries();
        return o;
    }();
    return t;
}

RenderSettings lodSettings(double pixels, int level) {
    RenderSettings s;
    s.detail.lodPixels = pixels;
    s.detail.level = level;
    return s;
}

}  // namespace

TEST(Lod, SummariesCountAverageAndPointIntoTheirSubtrees) {
    const Octree& t = summarized();
    ASSERT_TRUE(t.hasSummaries());
    EXPECT_EQ(t.summaries()[0].voxelCount, t.voxels().size());
    // Every node's count is the sum of its children's; its first voxel lies inside it; its
    // mean height lies inside its z range.
    struct Item { std::uint32_t node; int level; ivec3 cell; };
    std::vector<Item> stack{{0u, 0, ivec3(0)}};
    std::vector<ivec3> cellOf(t.voxels().size());
    t.forEachVoxel([&](const ivec3& c, std::uint32_t v) { cellOf[v] = c; });
    std::size_t checked = 0;
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const OctreeNode& n = t.nodes()[it.node];
        const NodeSummary& s = t.summaries()[it.node];
        std::uint64_t sum = 0;
        std::uint32_t slot = n.firstChild;
        for (int c = 0; c < 8; ++c) {
            if (!(n.childMask & (1u << c))) continue;
            const ivec3 cc = it.cell * 2 + ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            if (it.level == t.depth - 1) {
                ++sum;
            } else {
                sum += t.summaries()[slot].voxelCount;
                stack.push_back({slot, it.level + 1, cc});
            }
            ++slot;
        }
        ASSERT_EQ(s.voxelCount, sum);
        const int shift = t.depth - it.level;
        const ivec3 first = cellOf[s.firstVoxel];
        EXPECT_EQ(first.x >> shift, it.cell.x);
        EXPECT_EQ(first.y >> shift, it.cell.y);
        EXPECT_EQ(first.z >> shift, it.cell.z);
        EXPECT_GE(s.meanZ, float(it.cell.z << shift));
        EXPECT_LE(s.meanZ, float((it.cell.z + 1) << shift));
        EXPECT_NEAR(glm::length(decodeNormal(s.normal)), 1.0f, 1e-3f);
        EXPECT_GT(t.occupancy(it.node, it.level), 0.0);
        EXPECT_LE(t.occupancy(it.node, it.level), 1.0);
        ++checked;
    }
    EXPECT_EQ(checked, t.nodes().size());
}

TEST(Lod, AverageNormalOfAFlatPatchIsItsNormal) {
    // A plane z = 0.1 x + 0.2: every voxel has (nearly) the same normal, so has every node
    // (the builder's orientation convention, whichever it is, kept).
    const ScalarField f = sampleFunction("plane", ivec3(33), dvec3(-1.0), dvec3(2.0 / 32),
                                         [](const dvec3& p) { return float(p.z - 0.1 * p.x - 0.2); });
    Octree t = buildShellOctree(f, {6, 0.0, 1});
    t.computeSummaries();
    const vec3 expected = glm::normalize(vec3(-0.1f, 0.0f, 1.0f));
    const vec3 voxelNormal = decodeNormal(t.voxels()[0].normal);
    EXPECT_GT(std::abs(glm::dot(voxelNormal, expected)), 0.999f);
    for (const NodeSummary& s : t.summaries()) EXPECT_GT(glm::dot(decodeNormal(s.normal), voxelNormal), 0.999f);
}

/// The tile renderer keeps its frontier above the cut's coarsest level and traces from it with
/// the cut: the same frame as full's, for several tile sizes and thread counts.
static void expectTileDrawsTheCutAsFull(const Octree& t, const Camera& camera, RenderSettings s, const Frame& full) {
    for (const auto& [tileSize, threads] : {std::pair{8, 2}, {3, 1}, {16, 3}}) {
        s.tileSize = tileSize;
        s.threads = threads;
        Frame tile;
        makeRenderer("tile")->render(t, camera, s, tile);
        const FrameDiff d = diffFrames(tile, full);
        EXPECT_TRUE(d.identical()) << "tile " << tileSize << ", threads " << threads << ": " << d.first;
    }
}

TEST(Lod, FullReferenceAndTileDrawTheSameCutTreeBitForBit) {
    // A sphere's coarse nodes reach beyond its bounding box: a cut must not be clipped by it.
    {
        Octree sphere = buildShellOctree(makeAnalyticField("sphere", 33), {6, 0.0, 0});
        sphere.computeSummaries();
        for (const NamedCamera& nc : generalTestCameras(sphere))
            for (const auto& [pixels, level] : {std::pair{0.0, 2}, {30.0, -1}, {12.0, -1}}) {
                SCOPED_TRACE("sphere, lod " + std::to_string(pixels) + ", level " + std::to_string(level) + ", " + nc.name);
                Frame full, ref;
                makeRenderer("full")->render(sphere, nc.camera, lodSettings(pixels, level), full);
                makeRenderer("reference")->render(sphere, nc.camera, lodSettings(pixels, level), ref);
                const FrameDiff d = diffFrames(full, ref);
                EXPECT_TRUE(d.identical()) << d.first;
                expectTileDrawsTheCutAsFull(sphere, nc.camera, lodSettings(pixels, level), full);
            }
    }
    const Octree& t = summarized();
    for (const auto& [pixels, level] : {std::pair{2.0, -1}, {6.0, -1}, {0.0, 4}, {3.0, 5}})
        for (const NamedCamera& nc : allTestCameras(t)) {
            SCOPED_TRACE(nc.name + ", lod " + std::to_string(pixels) + ", level " + std::to_string(level));
            Frame full, ref;
            const RenderSettings s = lodSettings(pixels, level);
            makeRenderer("full")->render(t, nc.camera, s, full);
            makeRenderer("reference")->render(t, nc.camera, s, ref);
            const FrameDiff d = diffFrames(full, ref);
            EXPECT_TRUE(d.identical()) << d.first;
            expectTileDrawsTheCutAsFull(t, nc.camera, s, full);
        }
}

TEST(Lod, DirectRenderersAgreeWithTheRayCastersUnderTheSameCut) {
    const Octree& t = summarized();
    for (const auto& [pixels, level] : {std::pair{3.0, -1}, {0.0, 4}})
        for (const NamedCamera& nc : generalTestCameras(t)) {
            SCOPED_TRACE(nc.name);
            const RenderSettings s = lodSettings(pixels, level);
            Frame ref, b2f, f2b;
            makeRenderer("reference")->render(t, nc.camera, s, ref);
            makeRenderer("direct")->render(t, nc.camera, s, b2f);
            makeRenderer("direct-f2b")->render(t, nc.camera, s, f2b);
            EXPECT_TRUE(diffFrames(b2f, f2b).identical());
            std::size_t either = 0, both = 0, same = 0;
            for (std::size_t i = 0; i < ref.hitId.size(); ++i) {
                const bool a = b2f.hitId[i] != kNoHit, r = ref.hitId[i] != kNoHit;
                either += a || r;
                both += a && r;
                same += a && b2f.hitId[i] == ref.hitId[i];
            }
            ASSERT_GT(either, 0u);
            EXPECT_GE(double(both), 0.999 * double(either));
            EXPECT_GE(double(same), 0.99 * double(either));
        }
}

TEST(Lod, ZeroPixelsAndTheVoxelLevelAreExactAndCoarserCutsVisitFewerNodes) {
    const Octree& t = summarized();
    const Camera cam = Camera::framing(cubeOf(t), 200, 150);
    Frame exact, none, lod2, lod8;
    const RenderStats se = makeRenderer("full")->render(t, cam, RenderSettings{}, exact);
    makeRenderer("full")->render(t, cam, lodSettings(0.0, t.depth), none);
    EXPECT_TRUE(diffFrames(exact, none).identical());
    EXPECT_FALSE(LodCut(t, cam, 0.0, -1).active());
    EXPECT_FALSE(LodCut(t, cam, 0.0, t.depth).active());
    const RenderStats s2 = makeRenderer("full")->render(t, cam, lodSettings(2.0, -1), lod2);
    const RenderStats s8 = makeRenderer("full")->render(t, cam, lodSettings(8.0, -1), lod8);
    EXPECT_LT(s2.nodesVisited, se.nodesVisited);
    EXPECT_LT(s8.nodesVisited, s2.nodesVisited);
    EXPECT_FALSE(diffFrames(exact, lod8).identical());
    // A node drawn whole shows its summary's first voxel as the hit id.
    std::size_t hits = 0;
    for (auto id : lod8.hitId) hits += id != kNoHit;
    EXPECT_GT(hits, 0u);
}

TEST(Lod, OrthographicCutIsALevelCut) {
    const Octree& t = summarized();
    Camera cam = Camera::framing(cubeOf(t), 160, 120);
    cam.frameOrthographic(cubeOf(t));
    // Pixel size in octree units; level l has edges of 2^(14-l) units. A cut of P pixels stops
    // at the first level whose edge is below P pixels.
    const double pixel = cam.orthoHeight / cam.height * std::ldexp(1.0, Octree::kIntBits) / t.cubeSide;
    const double pixels = std::ldexp(1.0, Octree::kIntBits - 5) / pixel * 1.01;  // level 5 is just below
    Frame a, b;
    makeRenderer("full")->render(t, cam, lodSettings(pixels, -1), a);
    makeRenderer("full")->render(t, cam, lodSettings(0.0, 5), b);
    EXPECT_TRUE(diffFrames(a, b).identical());
}

TEST(Lod, RenderersWithoutAMultiResolutionModeAndTreesWithoutSummariesRefuse) {
    const Octree& t = summarized();
    const Camera cam = Camera::framing(cubeOf(t), 40, 30);
    Frame f;
    for (const char* name : {"linear", "area", "area+colour", "area-exact"})
        EXPECT_THROW(render(name, t, cam, f, lodSettings(2.0, -1)), UsageError) << name;
    EXPECT_THROW(makeRenderer("full")->render(noiseTree(), cam, lodSettings(2.0, -1), f), UsageError);
}

TEST(Lod, ProgressiveRenderingDeliversCoarseFramesThenTheExactOneAndStopsWhenAsked) {
    const Octree& t = summarized();
    const Camera cam = Camera::framing(cubeOf(t), 120, 90);
    Frame exact, f;
    makeRenderer("full")->render(t, cam, RenderSettings{}, exact);
    std::vector<double> seen;
    const int n = renderProgressive(*makeRenderer("full"), t, cam, RenderSettings{}, f, [&](const Frame&, double p) {
        seen.push_back(p);
        return true;
    });
    EXPECT_EQ(n, 4);
    EXPECT_EQ(seen, (std::vector<double>{8.0, 4.0, 2.0, 0.0}));
    EXPECT_TRUE(diffFrames(exact, f).identical());
    // Cancelled after the first frame.
    seen.clear();
    EXPECT_EQ(renderProgressive(*makeRenderer("direct"), t, cam, RenderSettings{}, f, [&](const Frame&, double p) {
                  seen.push_back(p);
                  return false;
              }),
              1);
    EXPECT_EQ(seen, (std::vector<double>{8.0}));
    // Without a multi-resolution mode: only the exact frame.
    EXPECT_EQ(renderProgressive(*makeRenderer("area"), t, cam, RenderSettings{}, f, [](const Frame&, double) { return true; }), 1);
    EXPECT_FALSE(makeRenderer("area")->multiResolution());
    EXPECT_TRUE(makeRenderer("direct-f2b")->multiResolution());
}
