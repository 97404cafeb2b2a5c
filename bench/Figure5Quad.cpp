// Paper B's Figure 5 as the paper ran it, in the plane: time against the number of rays for
// beam tracing and Samet's one-ray-at-a-time tracing over quadtrees of a random scene and of the
// 2D SphereFlake (bench/quadtree/Quadtree2D.h). For each ray count the two tracers
// run alternately, REPEAT times each, on one thread, and the fastest of each is kept (a change in
// the machine's load hits both alike); every ray's hit is compared with the brute force's.
//
// Usage: octrace_figure5_2d [REPEAT] [MAX_RAYS]
// Prints one JSON object. Built with -DOCTRACE_BUILD_BENCH=ON; run by bench/figure5_2d.py.
#include "quadtree/Quadtree2D.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace octrace;
using namespace octrace::quad;

namespace {

struct SceneSpec {
    const char* key;
    const char* description;
    Scene2D scene;
    int leafObjects;
    dvec2 eye;
};

std::size_t mismatches(const std::vector<Hit2D>& a, const std::vector<Hit2D>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] == b[i] ? 0 : 1;
    return n;
}

}  // namespace

int main(int argc, char** argv) {
    const int repeat = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    const std::size_t maxRays = argc > 2 ? std::size_t(std::atoll(argv[2])) : 1000000;
    // Leaf thresholds chosen so that the occupied leaves come near the paper's 106 (random)
    // and 140 (SphereFlake); the eye sits left of the scene, a little below its middle.
    std::vector<SceneSpec> scenes;
    scenes.push_back({"random", "78 random circles (seed 1), at most 1 per leaf", makeRandom2D(78, 1), 1, dvec2(-1.5, 0.4)});
    scenes.push_back({"flake", "2D SphereFlake level 3 (187 circles), at most 5 per leaf", makeFlake2D(3), 5, dvec2(-2.5, -0.3)});
    std::vector<std::size_t> counts;
    for (std::size_t n = 100; n <= maxRays; n *= 10) {
        counts.push_back(n);
        if (n * 3 <= maxRays) counts.push_back(n * 3);
    }
    std::printf("{\n  \"repeat\": %d,\n  \"threads\": 1,\n  \"scenes\": [\n", repeat);
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const SceneSpec& sp = scenes[s];
        Quadtree tree = Quadtree::build(sp.scene, sp.leafObjects);
        std::printf("    {\"key\": \"%s\", \"description\": \"%s\", \"circles\": %zu, \"leaf_objects\": %d, "
                    "\"nodes\": %zu, \"leaves\": %zu, \"occupied_leaves\": %zu, \"depth\": %d, \"eye\": [%g, %g],\n"
                    "     \"points\": [\n",
                    sp.key, sp.description, tree.scene.circles.size(), sp.leafObjects, tree.nodes.size(), tree.leaves(),
                    tree.occupiedLeaves(), tree.depth, sp.eye.x, sp.eye.y);
        for (std::size_t k = 0; k < counts.size(); ++k) {
            const Fan fan = fanOver(tree, sp.eye, counts[k]);
            double bestSamet = 1e300, bestBeam = 1e300;
            Trace2DCounters cs, cb;
            std::vector<Hit2D> samet, beams;
            for (int r = 0; r < repeat; ++r) {
                cs = {};
                Timer ts;
                samet = traceSamet(tree, fan, cs);
                bestSamet = std::min(bestSamet, ts.ms());
                cb = {};
                Timer tb;
                beams = traceBeams(tree, fan, cb);
                bestBeam = std::min(bestBeam, tb.ms());
            }
            const auto ref = traceBruteForce(tree.scene, fan);
            std::size_t hits = 0;
            for (const auto& h : ref) hits += h.hit() ? 1 : 0;
            std::printf("       {\"rays\": %zu, \"samet_ms\": %.4f, \"beam_ms\": %.4f, \"speedup\": %.3f, \"rays_hit\": %zu, "
                        "\"samet_mismatched_rays\": %zu, \"beam_mismatched_rays\": %zu, \"samet_leaves\": %llu, "
                        "\"samet_intersections\": %llu, \"beams\": %llu, \"beam_rays_selected\": %llu, "
                        "\"beam_intersections\": %llu}%s\n",
                        counts[k], bestSamet, bestBeam, bestSamet / bestBeam, hits, mismatches(samet, ref),
                        mismatches(beams, ref), (unsigned long long)cs.nodes, (unsigned long long)cs.intersections,
                        (unsigned long long)cb.beams, (unsigned long long)cb.raySelections,
                        (unsigned long long)cb.intersections, k + 1 < counts.size() ? "," : "");
            std::fflush(stdout);
        }
        std::printf("     ]}%s\n", s + 1 < scenes.size() ? "," : "");
    }
    std::printf("  ]\n}\n");
    return 0;
}
