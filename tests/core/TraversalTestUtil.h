#pragma once
// Ray generators shared by the traversal tests.
#include "../TestScale.h"
#include "octrace/build/CityModel.h"
#include "octrace/build/CityVoxelizer.h"
#include "octrace/octree/Octree.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/ReferenceTraversal.h"
#include "octrace/util/Parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <random>
#include <sstream>

namespace octrace::testutil {

constexpr double kL = double(1 << Octree::kIntBits);

/// The cells of a tree's boundary voxels (forEachVoxel walks the whole tree: built once per
/// tree, then shared read-only by every thread). Holds a copy, not the tree: a cache keyed by
/// the tree's address went stale when a later tree was built at the same address (a test's
/// local octree after the previous test's), and indexed past its end.
class VoxelCells {
public:
    explicit VoxelCells(const Octree& t) : depth_(t.depth), cells_(t.voxels().size()) {
        t.forEachVoxel([&](const ivec3& c, std::uint32_t i) { cells_[i] = c; });
    }
    /// A random boundary voxel's cell (the tree must have one).
    ivec3 random(std::mt19937_64& rng) const {
        return cells_[std::uniform_int_distribution<std::size_t>(0, cells_.size() - 1)(rng)];
    }
    int depth() const { return depth_; }

private:
    int depth_;
    std::vector<ivec3> cells_;
};

/// Ground at z = 1 to terrain depth 3 and a house to depth 6 in a 64-unit cube: coarse leaves.
inline const Octree& coarseLeafTree() {
    static const Octree t = [] {
        CityModel m;
        m.objects.push_back({"ground", "TINRelief", CityRole::Terrain, packColour(vec3(0, 1, 0))});
        m.objects.push_back({"house", "Building", CityRole::Solid, packColour(vec3(1, 0, 0))});
        m.addPolygon({{{0, 0, 1}, {64, 0, 1}, {64, 64, 1}, {0, 64, 1}}}, 0);
        m.addPrism({{{8, 8}, {24, 8}, {24, 24}, {8, 24}}}, 1.0, 17.0, 1);
        m.addPolygon({{{0, 0, 64}, {1, 0, 64}, {0, 1, 64}}}, 1);
        CityBuildOptions o;
        o.depth = 6;
        o.terrainDepth = 3;
        return voxelizeCity(m, o);
    }();
    return t;
}

/// Eye somewhere around the cube (outside), looking at a random point of a random voxel.
inline void rayAtVoxel(const VoxelCells& cells, std::mt19937_64& rng, dvec3& o, dvec3& d) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const ivec3 c = cells.random(rng);
    const double vs = kL / double(1 << cells.depth());
    dvec3 target = (dvec3(c) + dvec3(u(rng), u(rng), u(rng))) * vs;
    dvec3 dir = glm::normalize(dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
    o = dvec3(kL * 0.5) + dir * kL * (1.0 + 2.0 * u(rng));
    d = target - o;
}

/// Eye anywhere in a box 3x the cube, random direction.
inline void randomRay(std::mt19937_64& rng, dvec3& o, dvec3& d) {
    std::uniform_real_distribution<double> u(-1.0, 2.0), n(-1.0, 1.0);
    o = dvec3(u(rng), u(rng), u(rng)) * kL;
    d = dvec3(n(rng), n(rng), n(rng));
}

/// Eye inside the cube, random direction.
inline void insideRay(std::mt19937_64& rng, dvec3& o, dvec3& d) {
    std::uniform_real_distribution<double> u(0.0, 1.0), n(-1.0, 1.0);
    o = dvec3(u(rng), u(rng), u(rng)) * kL;
    d = dvec3(n(rng), n(rng), n(rng));
}

/// A ray whose quantized line passes exactly through node corners and edges: both points on
/// the main planes lie on the lattice of spacing g = 2^(N-l) (the corners of the nodes of
/// level l), and the offsets between them are 0 or +-g*2^e, so that the line meets lattice
/// points of that level (u and v planes crossed at the same point: corners and edges).
/// Random level, main axis and signs.
inline void latticeRay(std::mt19937_64& rng, dvec3& o, dvec3& d) {
    std::uniform_int_distribution<int> axis(0, 2), bit(0, 1), ldist(0, 10), pick(0, 4);
    const int N = Octree::kIntBits;
    int main = axis(rng), l = ldist(rng);
    const double g = std::ldexp(1.0, N - l);
    std::uniform_int_distribution<int> cellIdx(0, (1 << l) - 1), edist(0, l);
    dvec3 a, b;
    a[main] = 0;
    b[main] = kL;
    for (int q = 0; q < 3; ++q) {
        if (q == main) continue;
        a[q] = g * cellIdx(rng);
        int kind = pick(rng);
        double delta = kind == 0 ? 0.0 : g * std::ldexp(1.0, edist(rng)) * (bit(rng) ? 1 : -1);
        if (std::abs(delta) > kL) delta = delta > 0 ? kL : -kL;
        b[q] = a[q] + delta;
    }
    if (bit(rng)) std::swap(a, b);  // direction along main negative
    d = b - a;
    o = a - d * 0.25;  // eye before a, outside, on the line (exact: powers of two)
}

inline std::string describe(const dvec3& o, const dvec3& d) {
    std::ostringstream s;
    s.precision(17);
    s << "o=(" << o.x << "," << o.y << "," << o.z << ") d=(" << d.x << "," << d.y << "," << d.z << ")";
    return s.str();
}

/// Traces with both and returns true when they agree (same voxel or both miss).
inline bool agree(const Octree& t, const dvec3& o, const dvec3& d, std::string* why = nullptr) {
    QuantizedRay q = quantizeRay(o, d);
    TraversalCounters c1, c2;
    TraversalHit a = traverseDiscrete(t, q, c1);
    TraversalHit b = traverseReference(t, referenceRayFromQuantized(q), c2);
    if (a.voxel == b.voxel && (!a.hit() || a.cell == b.cell)) return true;
    if (why) {
        std::ostringstream s;
        s << describe(o, d) << " discrete=" << a.voxel << " (" << a.cell.x << "," << a.cell.y << "," << a.cell.z
          << ") reference=" << b.voxel << " (" << b.cell.x << "," << b.cell.y << "," << b.cell.z << ")";
        *why = s.str();
    }
    return false;
}

struct Tally {
    std::atomic<long> rays{0}, hits{0}, mismatches{0};
    std::mutex m;
    std::string first;
};

/// Runs `count` rays (times OCTRACE_TEST_SCALE, see TestScale.h) from `gen` (seeded per
/// chunk) through both traversals, in parallel.
template <class Gen>
void runRays(const Octree& t, long count, std::uint64_t seed, Gen gen, Tally& tally) {
    count = scaledCount(count);
    const long chunk = 10000;
    const std::size_t chunks = std::size_t((count + chunk - 1) / chunk);
    parallelFor(chunks, 0, [&](std::size_t ci) {
        std::mt19937_64 rng(seed * 1000003u + ci);
        long n = std::min(chunk, count - long(ci) * chunk);
        for (long i = 0; i < n; ++i) {
            dvec3 o, d;
            gen(rng, o, d);
            std::string why;
            QuantizedRay q = quantizeRay(o, d);
            TraversalCounters c;
            if (traverseDiscrete(t, q, c).hit()) ++tally.hits;
            ++tally.rays;
            if (!agree(t, o, d, &why)) {
                if (tally.mismatches++ == 0) {
                    std::lock_guard<std::mutex> lock(tally.m);
                    tally.first = why;
                }
            }
        }
    });
}

}  // namespace octrace::testutil
