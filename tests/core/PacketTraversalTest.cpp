// The packet traversal (render/traversal/PacketTraversal.h): every lane finds the hit of the
// scalar traversal from the same node, on every instruction set the processor runs, with and without a filter that
// passes voxels, on shell, volume-form and mixed-depth (coarse leaf) trees, for rays aimed into
// the node, rays from an eye inside it, and rays through node corners and edges.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Lod.h"
#include "render/traversal/PacketTraversal.h"
#include "TraversalTestUtil.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>
#include <vector>

using namespace octrace;
using namespace octrace::detail;
using octrace::testutil::kL;

namespace {

struct NamedTree {
    std::string name;
    const Octree* tree;
};

std::vector<NamedTree> packetTrees() {
    static const Octree sphere = buildShellOctree(makeAnalyticField("sphere", 33), {6, 0.0, 0});
    static const Octree noise = buildShellOctree(makeAnalyticField("noise", 65, 7), {8, 0.0, 0});
    static const Octree torus = [] {
        BuildOptions o{6, 0.0, 0};
        o.form = OctreeForm::Volume;
        return buildOctree(makeAnalyticField("torus", 33), o);
    }();
    // Three small spheres at depth 12 (radii of 20-40 voxels): the deepest levels' steps.
    static const Octree deep = [] {
        BuildOptions o{12, 0.0, 0};
        return buildShellOctree(sampleFunction("small spheres", ivec3(65), dvec3(-1.0), dvec3(2.0 / 64), [](const dvec3& p) {
                                    const double a = 0.02 - glm::length(p - dvec3(0.3, -0.2, 0.1));
                                    const double b = 0.03 - glm::length(p - dvec3(-0.41, 0.37, -0.26));
                                    const double c = 0.015 - glm::length(p - dvec3(0.05, 0.52, 0.61));
                                    return float(std::max({a, b, c}));
                                }),
                                o);
    }();
    return {{"sphere", &sphere}, {"noise", &noise}, {"torus, volume form", &torus},
            {"city with coarse leaves", &testutil::coarseLeafTree()}, {"small spheres at depth 12", &deep}};
}

/// The inner nodes of a tree by level (interior terms left out: nothing is below them).
std::vector<std::vector<StartNode>> innerNodes(const Octree& t) {
    std::vector<std::vector<StartNode>> byLevel(std::size_t(t.depth));
    for (int level = 0; level < t.depth; ++level)
        t.forEachAtLevel(level, [&](const ivec3& cell, std::uint32_t index) {
            if (t.nodes()[index].childMask) byLevel[std::size_t(level)].push_back({index, level, cell});
        });
    return byLevel;
}

bool sameHit(const TraversalHit& a, const TraversalHit& b) {
    return a.voxel == b.voxel && a.node == b.node &&
           (!a.hit() || (a.cell == b.cell && a.leafShift == b.leafShift && a.level == b.level));
}

struct Counts {
    long lanes = 0, hits = 0, misses = 0, passed = 0;
    long scalar = 0;    ///< lanes the packet handed to the scalar traversal
    long nodeHits = 0;  ///< lanes whose hit is a node a cut draws whole
};

const char* isaName(PacketIsa isa) { return isa == PacketIsa::Avx512 ? "avx512" : isa == PacketIsa::Avx2 ? "avx2" : "sse2"; }

/// The instruction sets this processor runs: SSE2 always, and those up to packetIsa().
std::vector<PacketIsa> runnableIsas() {
    std::vector<PacketIsa> v;
    for (const PacketIsa isa : {PacketIsa::Sse2, PacketIsa::Avx2, PacketIsa::Avx512})
        if (int(isa) <= int(packetIsa())) v.push_back(isa);
    return v;
}

/// One packet on `isa`: the lanes' hits against the scalar traversal's.
void checkPacket(PacketIsa isa, const Octree& t, const StartNode& start, const std::vector<QuantizedRay>& rays,
                 const VoxelFilter* filter, Counts& counts, const std::string& what, bool allInPacket,
                 const LodCut* cut) {
    ASSERT_LE(rays.size(), packetLanes(isa));
    std::vector<TraversalHit> expected(rays.size());
    for (std::size_t l = 0; l < rays.size(); ++l) {
        TraversalCounters c;
        expected[l] = traverseFromNodes(t, rays[l], &start, 1, c, filter, cut);
        if (filter && !sameHit(expected[l], traverseFromNodes(t, rays[l], &start, 1, c, nullptr, cut))) ++counts.passed;
        if (expected[l].nodeHit()) ++counts.nodeHits;
        ++counts.lanes;
        ++(expected[l].hit() ? counts.hits : counts.misses);
    }
    std::vector<TraversalHit> got(rays.size());
    PacketLane lanes[kMaxPacketLanes];
    for (std::size_t l = 0; l < rays.size(); ++l) lanes[l] = PacketLane{&rays[l], filter, &got[l]};
    TraversalCounters c;
    unsigned scalar = 0;
    const unsigned found = traversePacket(isa, t, start, lanes, unsigned(rays.size()), c, cut, &scalar);
    counts.scalar += std::popcount(scalar);
    // A node of level 4 or finer, the eye far from it along every ray's main axis: every lane is
    // the packet's own (its values are within the bound, the eye's plane does not cut the node).
    if (allInPacket) {
        ASSERT_EQ(scalar, 0u) << what << " " << isaName(isa);
    }
    for (std::size_t l = 0; l < rays.size(); ++l) {
        const bool f = found >> l & 1u;
        ASSERT_EQ(f, expected[l].hit()) << what << " lane " << l << " " << isaName(isa);
        if (f) {
            ASSERT_TRUE(sameHit(got[l], expected[l]))
                << what << " lane " << l << " " << isaName(isa) << ": voxel " << got[l].voxel << " instead of "
                << expected[l].voxel;
        }
    }
}

/// Rays grouped into packets of one main axis and sign pattern (the packet's requirement), on
/// every instruction set this processor runs, each with its own packet width.
void checkGrouped(const Octree& t, const StartNode& start, const std::vector<QuantizedRay>& rays, const VoxelFilter* filter,
                  Counts& counts, const std::string& what, bool allInPacket = false, const LodCut* cut = nullptr) {
    for (const PacketIsa isa : runnableIsas()) {
        std::vector<QuantizedRay> groups[3][8];
        for (const QuantizedRay& q : rays) {
            if (!q.meetsCube) continue;
            std::vector<QuantizedRay>& g = groups[q.main][q.sign];
            g.push_back(q);
            if (g.size() == packetLanes(isa)) {
                checkPacket(isa, t, start, g, filter, counts, what, allInPacket, cut);
                g.clear();
            }
        }
        for (auto& byMain : groups)
            for (auto& g : byMain)
                if (!g.empty()) checkPacket(isa, t, start, g, filter, counts, what, allInPacket, cut);
    }
}

}  // namespace

TEST(PacketTraversal, EveryLaneFindsTheScalarTraversalsHitOnEveryInstructionSet) {
    // This machine's best is among those checked (on a processor without AVX2 only SSE2 runs).
    EXPECT_EQ(runnableIsas().back(), packetIsa());
    // Voxels with (7x + 3y + z) % 4 == 0 are passed, as a smooth surface passes the voxels its
    // interpolant misses: the lane goes on behind them.
    const VoxelFilter passSome = [](TraversalHit& h) { return (7 * h.cell.x + 3 * h.cell.y + h.cell.z) % 4 != 0; };
    for (const NamedTree& nt : packetTrees()) {
        const Octree& t = *nt.tree;
        const auto nodes = innerNodes(t);
        std::mt19937_64 rng(17);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        Counts counts;
        for (int trial = 0; trial < 1500; ++trial) {
            const int level = int(rng() % std::uint64_t(t.depth));
            if (nodes[std::size_t(level)].empty()) continue;
            const auto& at = nodes[std::size_t(level)];
            const StartNode start = at[rng() % at.size()];
            const double side = kL / double(1 << level);
            const dvec3 lo = dvec3(start.cell) * side;
            // The eye: far outside, near (a few sides), or inside the node's box (the eye's
            // plane then cuts it: those lanes go to the scalar traversal).
            const int kind = trial % 3;
            const dvec3 dir = glm::normalize(dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
            const dvec3 eye = kind == 2 ? lo + dvec3(u(rng), u(rng), u(rng)) * side
                                        : lo + dvec3(0.5 * side) + dir * side * (kind == 0 ? 8.0 : 1.5);
            std::vector<QuantizedRay> rays;
            for (int i = 0; i < 32; ++i) {
                // Aimed at a point of the box widened by a tenth, some rays miss it.
                const dvec3 target = lo + (dvec3(u(rng), u(rng), u(rng)) * 1.2 - 0.1) * side;
                rays.push_back(quantizeRay(eye, target - eye));
            }
            const std::string what = nt.name + ", node " + std::to_string(start.node) + " at level " + std::to_string(level) +
                                     ", trial " + std::to_string(trial);
            checkGrouped(t, start, rays, trial % 2 ? &passSome : nullptr, counts, what, kind == 0 && level >= 4);
            if (HasFatalFailure()) return;
        }
        // Rays through node corners and edges, from the root and from a node below it.
        for (int trial = 0; trial < 300; ++trial) {
            std::vector<QuantizedRay> rays;
            for (int i = 0; i < 64; ++i) {
                dvec3 o, d;
                testutil::latticeRay(rng, o, d);
                rays.push_back(quantizeRay(o, d));
            }
            const int level = trial % 2 ? 0 : 1 + int(rng() % std::uint64_t(t.depth - 1));
            if (nodes[std::size_t(level)].empty()) continue;
            const auto& at = nodes[std::size_t(level)];
            checkGrouped(t, at[rng() % at.size()], rays, trial % 3 ? nullptr : &passSome, counts,
                         nt.name + ", lattice rays, trial " + std::to_string(trial));
            if (HasFatalFailure()) return;
        }
        // Both outcomes occur often, and the filter had voxels to pass.
        EXPECT_GT(counts.hits, counts.lanes / 20) << nt.name;
        EXPECT_GT(counts.misses, counts.lanes / 20) << nt.name;
        EXPECT_GT(counts.passed, 0) << nt.name;
        // Most lanes went through the packet's own arithmetic, some (eye inside) through the scalar one.
        EXPECT_LT(counts.scalar, counts.lanes / 2) << nt.name;
        EXPECT_GT(counts.scalar, 0) << nt.name;
    }
}

TEST(PacketTraversal, UnderACutEveryLaneFindsTheScalarTraversalsNodeOrVoxel) {
    // The cut stops at nodes by level and by projected size (Lod.h): the same for every lane, so
    // a packet stops all the lanes that reach such a node there, as the scalar traversal does.
    Octree t = buildShellOctree(makeAnalyticField("noise", 65, 7), {8, 0.0, 0});
    t.computeSummaries();
    const auto nodes = innerNodes(t);
    const Camera camera = Camera::framing(Box3{t.cubeOrigin, t.cubeOrigin + dvec3(t.cubeSide)}, 1600, 1200);
    const VoxelFilter passSome = [](TraversalHit& h) { return (7 * h.cell.x + 3 * h.cell.y + h.cell.z) % 4 != 0; };
    long voxelHits = 0;
    for (const auto& [pixels, level] : {std::pair{5.0, -1}, {0.0, 5}, {12.0, 6}}) {
        const LodCut cut(t, camera, pixels, level);
        ASSERT_TRUE(cut.active());
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        Counts counts;
        for (int trial = 0; trial < 600; ++trial) {
            // Start nodes above the coarsest level the cut stops at, as the tile renderer's.
            const int startLevel = int(rng() % std::uint64_t(std::max(1, cut.coarsestLevel())));
            if (startLevel >= cut.coarsestLevel() || nodes[std::size_t(startLevel)].empty()) continue;
            const auto& at = nodes[std::size_t(startLevel)];
            const StartNode start = at[rng() % at.size()];
            const double side = kL / double(1 << startLevel);
            const dvec3 lo = dvec3(start.cell) * side;
            const dvec3 dir = glm::normalize(dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
            const dvec3 eye = lo + dvec3(0.5 * side) + dir * side * (trial % 2 ? 6.0 : 1.5);
            std::vector<QuantizedRay> rays;
            for (int i = 0; i < 32; ++i) {
                const dvec3 target = lo + (dvec3(u(rng), u(rng), u(rng)) * 1.2 - 0.1) * side;
                rays.push_back(quantizeRay(eye, target - eye));
            }
            checkGrouped(t, start, rays, trial % 3 ? nullptr : &passSome, counts,
                         "lod " + std::to_string(pixels) + ", level " + std::to_string(level) + ", trial " + std::to_string(trial),
                         false, &cut);
            if (HasFatalFailure()) return;
        }
        EXPECT_GT(counts.nodeHits, counts.lanes / 50) << pixels << " " << level;
        voxelHits += counts.hits - counts.nodeHits;
    }
    EXPECT_GT(voxelHits, 0);  // the size cut of 5 pixels lets some rays reach voxels
}
