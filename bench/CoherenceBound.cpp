// How much can any trajectory- or colour-coherence scheme save on a scene? Measures, in one
// process and alternately, the `full` renderer and the same per-pixel pipeline with every
// traversal replaced by a look-up of the hit `full` found (an oracle that costs nothing):
// outline tests, ray quantization, shading, depth and frame writes stay. The oracle frame's
// time is a floor for every renderer that quantizes and writes each pixel as the discrete
// renderers do, so full / floor bounds their speed-up. A second floor also leaves out the
// quantization of rays (what colour coherence could skip at best) and a third the shading.
//
// Usage: octrace_coherence_bound FIELD VAR ISO REGION DEPTH CAMPOS LOOKAT UP FOV WxH [REPEAT]
// Prints one JSON object. Built with -DOCTRACE_BUILD_BENCH=ON; run by bench/coherence_bound.py.
#include "../core/src/render/traversal/PixelRays.h"

#include "octrace/build/OctreeBuilder.h"
#include "octrace/io/FieldReader.h"
#include "octrace/render/Renderer.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

using namespace octrace;

namespace {

dvec3 parseVec(const std::string& s) {
    dvec3 v(0.0);
    std::stringstream in(s);
    char comma;
    in >> v.x >> comma >> v.y >> comma >> v.z;
    return v;
}

enum class Floor { Quantize, NoQuantize, NoShade };

/// The per-pixel work of the discrete renderers (single thread, row by row as they go), with
/// the hit of every pixel taken from `hits`.
double floorFrame(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                  const std::vector<TraversalHit>& hits, Floor mode, Frame& frame, std::uint64_t& checksum) {
    Timer timer;
    frame.resize(camera.width, camera.height);
    const Shader shader(tree, camera, settings);
    const detail::PixelRays rays(tree, camera);
    std::vector<ivec3> cells(frame.hitId.size(), ivec3(0));
    std::uint64_t meets = 0;
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const std::size_t p = frame.pixel(x, y);
            frame.flags[p] = Frame::kTraced;
            if (!rays.mayMeetCube(x, y)) {
                frame.rgba[p] = settings.background;
                continue;
            }
            const dvec3 dir = rays.direction(x, y);
            if (mode == Floor::Quantize) meets += rays.quantized(x, y, dir).meetsCube;
            const TraversalHit& hit = hits[p];
            if (!rays.mayHitSurface(x, y) || !hit.hit()) {
                frame.rgba[p] = settings.background;
                continue;
            }
            frame.hitId[p] = hit.voxel;
            cells[p] = hit.cell;
            if (mode == Floor::NoShade) continue;
            frame.rgba[p] = shader.shade(hit);
            frame.depth[p] = shader.distance(rays.world(x, y, dir), hit);
        }
    const double ms = timer.ms();
    checksum += meets + std::uint64_t(cells[cells.size() / 2].x);
    return ms;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 11) {
        std::fprintf(stderr, "usage: %s FIELD VAR ISO REGION DEPTH CAMPOS LOOKAT UP FOV WxH [REPEAT]\n", argv[0]);
        return 2;
    }
    try {
        io::FieldRequest req;
        req.variable = argv[2];
        const auto region = io::parseRegion(argv[4]);
        req.hasRegion = true;
        std::copy(region.begin(), region.end(), req.region);
        const ScalarField field = io::readField(argv[1], req);
        BuildOptions opt;
        opt.depth = std::atoi(argv[5]);
        opt.iso = std::atof(argv[3]);
        Octree tree = buildShellOctree(field, opt);
        Camera camera;
        camera.position = parseVec(argv[6]);
        camera.lookAt = parseVec(argv[7]);
        camera.up = parseVec(argv[8]);
        camera.fovYDegrees = std::atof(argv[9]);
        if (std::sscanf(argv[10], "%dx%d", &camera.width, &camera.height) != 2) throw UsageError("bad size");
        const int repeat = argc > 11 ? std::atoi(argv[11]) : 5;
        RenderSettings settings;
        settings.threads = 1;

        // The hits of `full`, per pixel (the oracle), and the check that they are its frame's.
        const auto full = makeRenderer("full");
        Frame fullFrame;
        RenderStats fullStats = full->render(tree, camera, settings, fullFrame);
        std::vector<TraversalHit> hits(fullFrame.hitId.size());
        {
            const detail::PixelRays rays(tree, camera);
            for (int y = 0; y < camera.height; ++y)
                for (int x = 0; x < camera.width; ++x) {
                    const std::size_t p = fullFrame.pixel(x, y);
                    if (fullFrame.hitId[p] == kNoHit) continue;
                    TraversalCounters c;
                    hits[p] = traverseDiscrete(tree, rays.quantized(x, y, rays.direction(x, y)), c);
                }
        }
        Frame frame;
        std::uint64_t checksum = 0;
        floorFrame(tree, camera, settings, hits, Floor::Quantize, frame, checksum);
        std::size_t differing = 0;
        for (std::size_t p = 0; p < frame.rgba.size(); ++p)
            differing += frame.hitId[p] != fullFrame.hitId[p] || frame.rgba[p] != fullFrame.rgba[p];

        // The traversal alone, split into rays that hit and rays that miss (inside the
        // surface's outline: the others are never traversed).
        std::vector<QuantizedRay> hitRays, missRays;
        {
            const detail::PixelRays rays(tree, camera);
            for (int y = 0; y < camera.height; ++y)
                for (int x = 0; x < camera.width; ++x) {
                    if (!rays.mayMeetCube(x, y) || !rays.mayHitSurface(x, y)) continue;
                    const QuantizedRay q = rays.quantized(x, y, rays.direction(x, y));
                    if (!q.meetsCube) continue;
                    (fullFrame.hitId[fullFrame.pixel(x, y)] != kNoHit ? hitRays : missRays).push_back(q);
                }
        }
        double bestTraverse[2] = {1e300, 1e300};
        std::uint64_t nodes[2] = {0, 0};
        for (int r = 0; r < repeat; ++r)
            for (int k = 0; k < 2; ++k) {
                TraversalCounters c;
                Timer t;
                for (const QuantizedRay& q : k == 0 ? hitRays : missRays) checksum += traverseDiscrete(tree, q, c).voxel;
                bestTraverse[k] = std::min(bestTraverse[k], t.ms());
                nodes[k] = c.nodes;
            }
        const auto area = makeRenderer("area");
        Frame areaFrame;
        double best[5] = {1e300, 1e300, 1e300, 1e300, 1e300};
        for (int r = 0; r < repeat; ++r) {
            best[0] = std::min(best[0], full->render(tree, camera, settings, fullFrame).renderMs);
            best[4] = std::min(best[4], area->render(tree, camera, settings, areaFrame).renderMs);
            best[1] = std::min(best[1], floorFrame(tree, camera, settings, hits, Floor::Quantize, frame, checksum));
            best[2] = std::min(best[2], floorFrame(tree, camera, settings, hits, Floor::NoQuantize, frame, checksum));
            best[3] = std::min(best[3], floorFrame(tree, camera, settings, hits, Floor::NoShade, frame, checksum));
        }
        std::printf("{\"traced_hits\": %zu, \"traverse_hits_ms\": %.3f, \"nodes_per_hit\": %.2f, \"traced_misses\": %zu, "
                    "\"traverse_misses_ms\": %.3f, \"nodes_per_miss\": %.2f, ",
                    hitRays.size(), bestTraverse[0], double(nodes[0]) / double(std::max<std::size_t>(hitRays.size(), 1)),
                    missRays.size(), bestTraverse[1], double(nodes[1]) / double(std::max<std::size_t>(missRays.size(), 1)));
        std::printf("\"depth\": %d, \"boundary_voxels\": %zu, \"pixels\": %llu, \"rays\": %llu, \"hits\": %llu, "
                    "\"nodes_per_ray\": %.3f, \"full_ms\": %.3f, \"floor_ms\": %.3f, \"floor_no_quantize_ms\": %.3f, "
                    "\"floor_no_shade_ms\": %.3f, \"area_ms\": %.3f, \"oracle_differing_pixels\": %zu, \"checksum\": %llu}\n",
                    opt.depth, tree.boundaryVoxels(), (unsigned long long)fullStats.pixels,
                    (unsigned long long)fullStats.rays, (unsigned long long)fullStats.hits,
                    double(fullStats.nodesVisited) / double(std::max<std::uint64_t>(fullStats.rays, 1)), best[0],
                    best[1], best[2], best[3], best[4], differing, (unsigned long long)checksum);
        return differing == 0 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "octrace_coherence_bound: %s\n", e.what());
        return 1;
    }
}
