#include "TraversalTestUtil.h"

#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/OrderTable.h"
#include "octrace/util/Parallel.h"

#include <atomic>
#include <limits>
#include <mutex>
#include <random>

using namespace octrace;
using namespace octrace::testutil;

namespace {

const Octree& sphereTree() {
    static Octree t = buildShellOctree(makeAnalyticField("sphere", 33), {6, 0.0, 0});
    return t;
}
const Octree& noiseTree() {
    static Octree t = buildShellOctree(makeAnalyticField("noise", 65, 7), {7, 0.0, 0});
    return t;
}
const Octree& gyroidTree() {
    // Anisotropic rectilinear grid: uneven z levels, like ocean depths.
    static Octree t = [] {
        ScalarField f = makeAnalyticField("gyroid", 40);
        f.spacing = dvec3(0.05, 0.08, 1.0);
        f.coords[2].resize(40);
        for (int k = 0; k < 40; ++k) f.coords[2][std::size_t(k)] = 0.02 * k + 0.004 * k * k;
        return buildShellOctree(f, {8, 0.0, 0});
    }();
    return t;
}

}  // namespace

TEST(OrderTable, MarksExactlyTheChainsAsProducible) {
    const OrderTable& t = OrderTable::instance();
    int producible = 0;
    for (unsigned s = 0; s < 8; ++s)
        for (unsigned b = 1; b < 256; ++b) {
            if (!t.producible(s, b)) continue;
            ++producible;
            auto e = t.entry(s, b);
            ASSERT_LE(OrderTable::count(e), 4);
            unsigned bits = 0;
            for (int i = 0; i < OrderTable::count(e); ++i) bits |= 1u << OrderTable::child(e, i);
            EXPECT_EQ(bits, b);
        }
    // The paper's example "0b01010011 -> 0,1,4,6" cannot occur: for no sign pattern is that
    // the visiting order (0 and 1 differ in z, 1 and 4 in x and z: not a monotone walk).
    for (unsigned s = 0; s < 8; ++s) {
        auto e = t.entry(s, 0b01010011);
        bool paperOrder = OrderTable::count(e) == 4 && OrderTable::child(e, 0) == 0 && OrderTable::child(e, 1) == 1 &&
                          OrderTable::child(e, 2) == 4 && OrderTable::child(e, 3) == 6;
        EXPECT_FALSE(paperOrder) << "sign " << s;
    }
    EXPECT_GT(producible, 8 * 8);
}

namespace {
/// Independent exact geometry: the children of the box [0,4)^3 (children of side 2) that the
/// line P + t*D crosses, with their entry parameters as fractions, under the documented
/// half-open rule (closed at the side the ray comes from).
struct Crossing {
    long num, den;
    int child;
};
std::vector<Crossing> crossedChildren(const ivec3& P, const ivec3& D, bool fromP) {
    std::vector<Crossing> out;
    for (int c = 0; c < 8; ++c) {
        ivec3 lo((c >> 2) & 1, (c >> 1) & 1, c & 1);
        lo *= 2;
        // Interval [sn/sd, en/ed) of t; start at -inf, end at +inf.
        long sn = fromP ? 0 : -1, sd = fromP ? 1 : 0, en = 1, ed = 0;  // den 0 = infinite; a ray starts at P
        auto lessF = [](long an, long ad, long bn, long bd) {  // a < b, den 0 = +-inf by sign of num
            if (ad == 0 && bd == 0) return an < bn;
            if (ad == 0) return an < 0;
            if (bd == 0) return bn > 0;
            return an * bd < bn * ad;
        };
        bool empty = false;
        for (int a = 0; a < 3; ++a) {
            int l = lo[a], h = lo[a] + 2;
            if (D[a] == 0) {
                if (!(P[a] >= l && P[a] < h)) empty = true;
                continue;
            }
            long s0n, s0d, e0n, e0d;
            if (D[a] > 0) { s0n = l - P[a]; e0n = h - P[a]; s0d = e0d = D[a]; }
            else { s0n = P[a] - h; e0n = P[a] - l; s0d = e0d = -D[a]; }
            if (lessF(sn, sd, s0n, s0d)) { sn = s0n; sd = s0d; }
            if (lessF(e0n, e0d, en, ed)) { en = e0n; ed = e0d; }
        }
        if (!empty && lessF(sn, sd, en, ed)) out.push_back({sn, sd, c});
    }
    std::sort(out.begin(), out.end(), [](const Crossing& a, const Crossing& b) {
        if (a.den == 0 || b.den == 0) return a.den == 0 && b.den != 0;
        return a.num * b.den < b.num * a.den;
    });
    return out;
}
}  // namespace

TEST(OrderTable, EveryEntryEqualsTheChildrenSortedByEntryParameterOfARayProducingIt) {
    const OrderTable& t = OrderTable::instance();
    std::vector<std::vector<int>> seen(8 * 256, std::vector<int>{-1});
    for (int px = -1; px <= 5; ++px)
        for (int py = -1; py <= 5; ++py)
            for (int pz = -1; pz <= 5; ++pz)
                for (int dx = -3; dx <= 3; ++dx)
                    for (int dy = -3; dy <= 3; ++dy)
                        for (int dz = -3; dz <= 3; ++dz) {
                            if (!dx && !dy && !dz) continue;
                            for (int fromP = 0; fromP < 2; ++fromP) {
                            ivec3 D(dx, dy, dz);
                            auto cr = crossedChildren(ivec3(px, py, pz), D, fromP == 1);
                            if (cr.empty()) continue;
                            unsigned s = (dx < 0 ? 4u : 0u) | (dy < 0 ? 2u : 0u) | (dz < 0 ? 1u : 0u);
                            unsigned byte = 0;
                            std::vector<int> order;
                            for (const auto& c : cr) {
                                byte |= 1u << c.child;
                                order.push_back(c.child);
                            }
                            ASSERT_TRUE(t.producible(s, byte)) << "sign " << s << " byte " << byte;
                            auto e = t.entry(s, byte);
                            ASSERT_EQ(OrderTable::count(e), int(order.size()));
                            for (std::size_t i = 0; i < order.size(); ++i)
                                ASSERT_EQ(OrderTable::child(e, int(i)), order[i]) << "sign " << s << " byte " << byte;
                            seen[s * 256 + byte] = order;
                            }
                        }
    // Every entry the table calls producible is produced by some ray of this family.
    int missing = 0;
    for (unsigned s = 0; s < 8; ++s)
        for (unsigned b = 1; b < 256; ++b)
            if (t.producible(s, b) && seen[s * 256 + b].size() == 1 && seen[s * 256 + b][0] == -1) {
                ++missing;
                ADD_FAILURE() << "no ray produced sign " << s << " byte " << b;
            }
    EXPECT_EQ(missing, 0);
}

TEST(DiscreteTraversal, MatchesReferenceOnRandomRaysThroughThreeOctrees) {
    const Octree* trees[] = {&sphereTree(), &noiseTree(), &gyroidTree()};
    long total = 0, hits = 0;
    for (int ti = 0; ti < 3; ++ti) {
        Tally tally;
        // Half aimed at voxels (mostly hits), half anywhere.
        const VoxelCells cells(*trees[ti]);
        runRays(*trees[ti], 150000, 11 + ti, [&cells](std::mt19937_64& r, dvec3& o, dvec3& d) { rayAtVoxel(cells, r, o, d); }, tally);
        runRays(*trees[ti], 150000, 21 + ti, [](std::mt19937_64& r, dvec3& o, dvec3& d) { randomRay(r, o, d); }, tally);
        EXPECT_EQ(tally.mismatches.load(), 0) << "tree " << ti << ": first mismatch " << tally.first;
        total += tally.rays;
        hits += tally.hits;
    }
    EXPECT_GE(total, 6 * scaledCount(150000));
    EXPECT_GE(double(hits) / double(total), 0.5) << hits << " hits of " << total;
}

TEST(DiscreteTraversal, MatchesReferenceOnRaysThroughNodeCornersAndEdges) {
    const Octree* trees[] = {&sphereTree(), &noiseTree(), &gyroidTree()};
    long total = 0;
    for (int ti = 0; ti < 3; ++ti) {
        Tally tally;
        runRays(*trees[ti], 40000, 31 + ti, [](std::mt19937_64& r, dvec3& o, dvec3& d) { latticeRay(r, o, d); }, tally);
        EXPECT_EQ(tally.mismatches.load(), 0) << "tree " << ti << ": first mismatch " << tally.first;
        total += tally.rays;
    }
    EXPECT_GE(total, 3 * scaledCount(40000));
}

TEST(DiscreteTraversal, MatchesReferenceWithTheEyeInsideTheCube) {
    const Octree* trees[] = {&sphereTree(), &noiseTree(), &gyroidTree()};
    for (int ti = 0; ti < 3; ++ti) {
        Tally tally;
        runRays(*trees[ti], 60000, 41 + ti, [](std::mt19937_64& r, dvec3& o, dvec3& d) { insideRay(r, o, d); }, tally);
        EXPECT_EQ(tally.mismatches.load(), 0) << "tree " << ti << ": first mismatch " << tally.first;
        EXPECT_GT(tally.hits.load(), 0);
    }
}

TEST(DiscreteTraversal, MatchesReferenceOnAxisParallelAndDiagonalRays) {
    const Octree* trees[] = {&sphereTree(), &noiseTree(), &gyroidTree()};
    const dvec3 dirs[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                          {1, 1, 0}, {1, -1, 0}, {0, 1, 1}, {-1, 0, 1}, {1, 1, 1}, {-1, 1, -1}};
    for (int ti = 0; ti < 3; ++ti) {
        Tally tally;
        for (const dvec3& dir : dirs) {
            runRays(*trees[ti], 3000, 51 + ti, [dir](std::mt19937_64& r, dvec3& o, dvec3& d) {
                std::uniform_real_distribution<double> u(0.0, 1.0);
                std::uniform_int_distribution<int> lattice(0, 64);
                // Half on lattice lines (exact node faces and edges), half anywhere; eye inside or out.
                for (int a = 0; a < 3; ++a) o[a] = (r() & 1) ? lattice(r) * (kL / 64) : u(r) * kL;
                o -= dir * (kL * u(r) * 1.2);
                d = dir;
            }, tally);
        }
        EXPECT_EQ(tally.mismatches.load(), 0) << "tree " << ti << ": first mismatch " << tally.first;
        EXPECT_GT(tally.hits.load(), 0);
    }
}

// Regression: rayAtVoxel kept the cells of the last tree it saw, keyed by the tree's address;
// a test that built a larger tree where a smaller one had been (the same local variable, or
// the next test's local at the same stack address) got the old cells and indexed past them
// (a crash in DiscreteTraversalRealData when its tests ran in one process). The cells now
// come from the tree they are built from: every ray aims at a voxel of the current tree.
TEST(DiscreteTraversal, RaysAimedAtVoxelsAimAtTheTreeInHandAfterAnotherOneAtTheSameAddress) {
    Octree t = buildShellOctree(makeAnalyticField("sphere", 17), {4, 0.0, 0});
    const std::size_t small = t.voxels().size();
    t = buildShellOctree(makeAnalyticField("noise", 65, 7), {7, 0.0, 0});
    ASSERT_GT(t.voxels().size(), 4 * small);
    const VoxelCells cells(t);
    std::mt19937_64 rng(5);
    long outside = 0, hits = 0;
    for (int i = 0; i < 2000; ++i) {
        outside += t.findVoxel(cells.random(rng)) == 0xFFFFFFFFu;
        dvec3 o, d;
        rayAtVoxel(cells, rng, o, d);
        TraversalCounters c;
        hits += traverseDiscrete(t, quantizeRay(o, d), c).hit();
    }
    EXPECT_EQ(outside, 0);
    EXPECT_GT(hits, 1900);
}

TEST(DiscreteTraversal, ProducesOnlyStateBytesTheOrderTableAccepts) {
    const OrderTable& table = OrderTable::instance();
    std::mt19937_64 rng(99);
    long bad = 0, seen = 0;
    unsigned firstSign = 0, firstByte = 0;
    const VoxelCells cells(noiseTree());
    auto observe = [&](unsigned s, unsigned b) {
        ++seen;
        if (b != 0 && !table.producible(s, b) && bad++ == 0) {
            firstSign = s;
            firstByte = b;
        }
    };
    for (int i = 0; i < 60000; ++i) {
        dvec3 o, d;
        if (i % 3 == 0) latticeRay(rng, o, d);
        else if (i % 3 == 1) rayAtVoxel(cells, rng, o, d);
        else insideRay(rng, o, d);
        TraversalCounters c;
        traverseDiscreteObserved(noiseTree(), quantizeRay(o, d), c, observe);
    }
    EXPECT_GT(seen, 100000);
    EXPECT_EQ(bad, 0) << "sign " << firstSign << " byte " << firstByte;
}

TEST(DiscreteTraversal, RaysThatMissTheCubeReportNoHitAndRaysBehindTheEyeDoNotCount) {
    const Octree& t = sphereTree();
    TraversalCounters c;
    // Pointing away from the cube.
    QuantizedRay away = quantizeRay(dvec3(-kL, kL / 2, kL / 2), dvec3(-1, 0, 0));
    EXPECT_FALSE(away.meetsCube);
    EXPECT_FALSE(traverseDiscrete(t, away, c).hit());
    // Passing beside it.
    QuantizedRay beside = quantizeRay(dvec3(-kL, 2.5 * kL, kL / 2), dvec3(1, 0, 0));
    EXPECT_FALSE(beside.meetsCube);
    // From the centre of the sphere outwards: the near wall behind the eye is not hit, the far one is.
    QuantizedRay out = quantizeRay(dvec3(kL / 2), dvec3(1, 0.1, 0.05));
    TraversalHit h = traverseDiscrete(t, out, c);
    ASSERT_TRUE(h.hit());
    EXPECT_GT(h.cell.x, (1 << t.depth) / 2);
}

TEST(TrajectoryCoherence, GuidedTraversalEqualsFullTraversalForAnyBranchNode) {
    // Exactness must not depend on the branch node being a good guess: pair each ray with the
    // branch node of its own hit and a nearby voxel, and with that of two unrelated voxels.
    const Octree* trees[] = {&sphereTree(), &noiseTree(), &gyroidTree()};
    for (int ti = 0; ti < 3; ++ti) {
        const Octree& t = *trees[ti];
        const VoxelCells cells(t);
        std::mt19937_64 rng(700 + ti);
        long certified = 0, total = 0, bad = 0;
        std::string first;
        for (int i = 0; i < 60000; ++i) {
            dvec3 o, d;
            if (i % 4 == 3) latticeRay(rng, o, d);
            else rayAtVoxel(cells, rng, o, d);
            QuantizedRay q = quantizeRay(o, d);
            TraversalCounters c;
            TraversalHit full = traverseDiscrete(t, q, c);
            ivec3 a = full.hit() && (i % 2 == 0) ? full.cell : cells.random(rng);
            ivec3 b = (i % 3 == 0) ? a : cells.random(rng);
            if (i % 2 == 0 && full.hit()) b = glm::clamp(a + ivec3(int(rng() % 3) - 1, int(rng() % 3) - 1, 0), ivec3(0),
                                                         ivec3((1 << t.depth) - 1));
            if (t.findVoxel(b) == 0xFFFFFFFFu) b = a;
            BranchNode bn = branchNode(t, a, b);
            ASSERT_TRUE(bn.valid());
            bool cert = false;
            TraversalHit g = traverseGuided(t, q, bn, c, cert);
            ++total;
            certified += cert;
            if (g.voxel != full.voxel && bad++ == 0) first = describe(o, d);
            if (cert) {
                EXPECT_TRUE(full.hit());
            }
        }
        EXPECT_EQ(bad, 0) << "tree " << ti << ": " << first;
        EXPECT_GT(certified, 0) << "tree " << ti;
        std::printf("tree %d: %ld of %ld guided rays certified\n", ti, certified, total);
    }
}

TEST(TrajectoryCoherence, StartingAtTheBranchNodeFindsAHitInsideItOrFallsBack) {
    const Octree& t = noiseTree();
    const VoxelCells cells(t);
    std::mt19937_64 rng(801);
    long fell = 0, inside = 0, differs = 0;
    for (int i = 0; i < 40000; ++i) {
        dvec3 o, d;
        rayAtVoxel(cells, rng, o, d);
        QuantizedRay q = quantizeRay(o, d);
        TraversalCounters c;
        TraversalHit full = traverseDiscrete(t, q, c);
        if (!full.hit()) continue;
        ivec3 b = glm::clamp(full.cell + ivec3(int(rng() % 5) - 2, int(rng() % 5) - 2, int(rng() % 5) - 2), ivec3(0),
                             ivec3((1 << t.depth) - 1));
        if (t.findVoxel(b) == 0xFFFFFFFFu) b = full.cell;
        BranchNode bn = branchNode(t, full.cell, b);
        bool fellBack = false;
        TraversalHit h = traverseFromBranch(t, q, bn, c, fellBack);
        ASSERT_TRUE(h.hit());
        if (fellBack) {
            ++fell;
            EXPECT_EQ(h.voxel, full.voxel);  // a retrace from the root is the full traversal
            continue;
        }
        ++inside;
        // The hit lies in the branch node's box, and is never behind the full traversal's hit.
        EXPECT_EQ(h.cell >> (t.depth - bn.level), bn.cell);
        differs += h.voxel != full.voxel;
    }
    EXPECT_GT(inside, fell);
    std::printf("branch starts: %ld inside, %ld fell back, %ld differ from full\n", inside, fell, differs);
}

// quantizeRays (eight lanes at a time with AVX-512 where the processor has it) gives every field
// of quantizeRay's result bit for bit: eyes outside, on and inside the cube and far off, every
// sign pattern and main axis, ties between axes, zero and tiny components, lines just missing
// the cube, and the scalar code's early returns (zero, infinite or NaN directions, eyes past the
// far plane) mixed into the same batches, and rays in any direction from eyes beside the cube
// (the line may cross the cube behind the eye: the eye's tests decide).
TEST(DiscreteTraversal, QuantizeRaysGivesQuantizeRayBitForBit) {
#if defined(__x86_64__) && defined(__GNUC__)
    if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512dq"))
        GTEST_SKIP() << "no AVX-512 F and DQ: quantizeRays is quantizeRay on this processor";
#endif
    const double L = double(std::int64_t(1) << Octree::kIntBits);
    const auto same = [](const QuantizedRay& a, const QuantizedRay& b) {
        return a.meetsCube == b.meetsCube && a.main == b.main && a.u == b.u && a.v == b.v && a.sign == b.sign && a.U0 == b.U0 &&
               a.dU == b.dU && a.V0 == b.V0 && a.dV == b.dV && a.eyeM == b.eyeM && a.uEyeFloor == b.uEyeFloor &&
               a.vEyeFloor == b.vEyeFloor;
    };
    {
        // A ray whose u on the lower main plane, om_u + t0 dm_u, falls on a rounding boundary of the
        // fixed point: rounding the product before the sum (quantizeRay) and fusing them into one
        // rounding give U0 = 409601 and 409600 (found by the review of the AVX-512 code, which GCC
        // had compiled with fused multiply-adds).
        const dvec3 eye(-81920.0, -40523.437979044305, -10426.038612372042), dir(1.0, 0.4958915783827468, 0.22727097915493213);
        const std::vector<dvec3> d(8, dir);
        std::vector<QuantizedRay> out(8);
        quantizeRays(eye, d.data(), 8, out.data());
        const QuantizedRay one = quantizeRay(eye, dir);
        EXPECT_EQ(one.U0, 409601);
        for (const QuantizedRay& q : out) EXPECT_TRUE(same(q, one)) << "U0 " << q.U0 << " against " << one.U0;
    }
    std::mt19937_64 rng(91);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<dvec3> eyes = {dvec3(-0.7, 1.9, 2.4) * L, dvec3(0.5, 0.5, 0.5) * L, dvec3(0.0), dvec3(L, L, 0.0),
                                     dvec3(0.25, -3.0, 0.6) * L, dvec3(40.0, -25.0, 90.0) * L, dvec3(1.5, 0.5, 0.5) * L,
                                     dvec3(0.5, 1.5, 0.5) * L, dvec3(0.5, 0.5, 1.5) * L, dvec3(0.4, -0.5, 0.6) * L};
    std::size_t lanes = 0, meeting = 0;
    for (const dvec3& eye : eyes)
        for (int batch = 0; batch < 200; ++batch) {
            const int n = 1 + int(rng() % 37);
            std::vector<dvec3> d(static_cast<std::size_t>(n));
            for (dvec3& v : d) {
                switch (rng() % 14) {
                    case 0: v = dvec3(u(rng), u(rng), 0.0); break;                       // a zero component
                    case 1: { const double a = u(rng); v = dvec3(a, -a, 0.5 * u(rng)); break; }  // |x| = |y|
                    case 8: { const double a = u(rng); v = dvec3(a, 0.5 * u(rng), a); break; }   // |x| = |z|
                    case 9: { const double a = u(rng); v = dvec3(0.5 * u(rng), a, -a); break; }  // |y| = |z|
                    case 10: { const double a = u(rng); v = dvec3(-a, a, a); break; }            // all three
                    case 2: v = dvec3(0.0); break;                                        // early return
                    case 3: v = dvec3(inf, u(rng), u(rng)); break;                        // early return
                    case 4: v = dvec3(u(rng), nan, u(rng)); break;
                    case 5: v = dvec3(1e-300, u(rng) * 1e-12, -1.0); break;               // tiny components
                    case 6:
                    case 7: v = dvec3(u(rng), u(rng), u(rng)); break;                     // any way, often away from the cube
                    default: v = glm::normalize(dvec3(0.5, 0.5, 0.5) * L + L * 0.8 * dvec3(u(rng), u(rng), u(rng)) - eye); break;
                }
            }
            std::vector<QuantizedRay> out(static_cast<std::size_t>(n));
            quantizeRays(eye, d.data(), n, out.data());
            for (int i = 0; i < n; ++i) {
                const QuantizedRay a = quantizeRay(eye, d[std::size_t(i)]), &b = out[std::size_t(i)];
                ASSERT_TRUE(same(a, b))
                    << "eye " << eye.x << "," << eye.y << "," << eye.z << " direction " << d[std::size_t(i)].x << ","
                    << d[std::size_t(i)].y << "," << d[std::size_t(i)].z;
                ++lanes;
                meeting += a.meetsCube;
            }
        }
    EXPECT_GT(meeting, lanes / 4);  // most rays are aimed at the cube
}
