// Micro-benchmarks of the single-ray traversals (Google Benchmark). Build with
// -DOCTRACE_BUILD_BENCH=ON; run build/bench/octrace_bench. Timings are reported, never asserted.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/ReferenceTraversal.h"

#include <benchmark/benchmark.h>

#include <map>
#include <random>

using namespace octrace;

namespace {
const Octree& tree(int which, int depth) {
    static std::map<std::pair<int, int>, Octree> cache;
    auto key = std::make_pair(which, depth);
    auto it = cache.find(key);
    if (it == cache.end())
        it = cache.emplace(key, buildShellOctree(makeAnalyticField(which == 0 ? "sphere" : "noise", 65, 7), {depth, 0.0, 0})).first;
    return it->second;
}

std::vector<QuantizedRay> rays(std::size_t n) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    const double L = double(1 << Octree::kIntBits);
    std::vector<QuantizedRay> out;
    dvec3 eye(1.7 * L, -0.9 * L, 1.4 * L);
    for (std::size_t i = 0; i < n; ++i) {
        dvec3 target = dvec3(0.5 * L) + dvec3(u(rng), u(rng), u(rng)) * L;
        out.push_back(quantizeRay(eye, target - eye));
    }
    return out;
}

void BM_Discrete(benchmark::State& state) {
    const Octree& t = tree(int(state.range(0)), int(state.range(1)));
    auto rs = rays(4096);
    TraversalCounters c;
    std::size_t i = 0, hits = 0;
    for (auto _ : state) {
        hits += traverseDiscrete(t, rs[i++ & 4095], c).hit();
    }
    state.counters["Voxels"] = double(t.boundaryVoxels());
    state.counters["NodesPerRay"] = double(c.nodes) / double(state.iterations());
    state.counters["HitRate"] = double(hits) / double(state.iterations());
}

void BM_Reference(benchmark::State& state) {
    const Octree& t = tree(int(state.range(0)), int(state.range(1)));
    auto rs = rays(4096);
    std::vector<ReferenceRay> refs;
    for (const auto& q : rs) refs.push_back(referenceRayFromQuantized(q));
    TraversalCounters c;
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(traverseReference(t, refs[i++ & 4095], c));
    state.counters["Voxels"] = double(t.boundaryVoxels());
}
void BM_QuantizeRay(benchmark::State& state) {
    const double L = double(1 << Octree::kIntBits);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    std::vector<dvec3> dirs;
    for (int i = 0; i < 4096; ++i) dirs.push_back(dvec3(0.5 * L) + dvec3(u(rng), u(rng), u(rng)) * L - dvec3(1.7 * L, -0.9 * L, 1.4 * L));
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(quantizeRay(dvec3(1.7 * L, -0.9 * L, 1.4 * L), dirs[i++ & 4095]));
}

/// Rays started at the branch node of their own hit and a neighbouring voxel: what the coherent
/// renderers pay per intermediate ray (approximate: range(2) == 0, exact guided: 1).
void BM_CoherentStart(benchmark::State& state) {
    const Octree& t = tree(int(state.range(0)), int(state.range(1)));
    auto rs = rays(4096);
    std::vector<BranchNode> branches;
    TraversalCounters c;
    for (const auto& q : rs) {
        TraversalHit h = traverseDiscrete(t, q, c);
        branches.push_back(h.hit() ? branchNode(t, h.cell, h.cell) : BranchNode{});
    }
    c = TraversalCounters{};
    std::size_t i = 0, certified = 0;
    for (auto _ : state) {
        const std::size_t k = i++ & 4095;
        bool flag = false;
        if (state.range(2) == 0) benchmark::DoNotOptimize(traverseFromBranch(t, rs[k], branches[k], c, flag));
        else benchmark::DoNotOptimize(traverseGuided(t, rs[k], branches[k], c, flag));
        certified += flag;
    }
    state.counters["NodesPerRay"] = double(c.nodes) / double(state.iterations());
    state.counters[state.range(2) == 0 ? "FellBack" : "Certified"] = double(certified) / double(state.iterations());
}
}  // namespace

BENCHMARK(BM_QuantizeRay);
BENCHMARK(BM_CoherentStart)->ArgsProduct({{0, 1}, {8, 9}, {0, 1}});
BENCHMARK(BM_Discrete)->ArgsProduct({{0, 1}, {7, 8, 9}});
BENCHMARK(BM_Reference)->ArgsProduct({{0, 1}, {7, 8, 9}});
BENCHMARK_MAIN();
