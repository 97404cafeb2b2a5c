#pragma once
// Private to core: what the ray-casting renderers of the voxel octree share around their
// traversals: writing a pixel from its hit (shading, depth, counters), and the per-pixel
// renderer that traces every pixel on its own, tile by tile.
#include "render/traversal/PixelRays.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/Renderer.h"
#include "octrace/render/Shading.h"
#include "octrace/render/SmoothSurface.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <vector>

namespace octrace::detail {

/// Whether surfaceHit tests `hit` (the frame draws smooth surfaces and the hit is a voxel the
/// test has not accepted yet); otherwise it returns the hit unchanged, and a caller may keep it
/// without the copy.
inline bool surfaceTestApplies(const SmoothSurface& smooth, const TraversalHit& hit) {
    return smooth.active() && hit.hit() && !hit.smooth;
}

/// The shared hit path of smooth surfaces (SmoothSurface.h), for every ray caster: the hit a
/// renderer proposes (the first boundary voxel on the pixel's ray) is tested against the field's
/// interpolant; a ray that passes it goes on with the discrete traversal under the same test
/// (from the root: the passed voxel is tested again and passed again, the traversal is exact).
/// The proposed hit unchanged when the frame draws voxels, and when it is smooth already (the
/// reference renderer runs its own test in its own traversal).
inline TraversalHit surfaceHit(const SmoothSurface& smooth, const TraversalHit& proposed, const PixelRays& rays, int x, int y,
                               const dvec3& dir, TraversalCounters& counters, const LodCut* cut = nullptr) {
    if (!surfaceTestApplies(smooth, proposed)) return proposed;
    SmoothSurface::RayState ray{rays.world(x, y, dir)};
    TraversalHit hit = proposed;
    if (smooth.test(ray, hit)) return hit;
    ray.side = -1;
    const VoxelFilter filter = smooth.filter(ray);
    return traverseDiscrete(smooth.tree(), rays.quantized(x, y, dir), counters, cut, &filter);
}

/// Writes pixel (x, y) as a miss (background, infinite depth, no hit) and counts it; what
/// writePixelHit writes for a ray that hits nothing.
inline void writeMissPixel(Frame& frame, int x, int y, const RenderSettings& settings, RenderStats& st) {
    const std::size_t p = frame.pixel(x, y);
    ++st.pixels;
    frame.flags[p] = Frame::kTraced;
    frame.rgba[p] = settings.background;
    frame.depth[p] = std::numeric_limits<float>::infinity();
    frame.hitId[p] = kNoHit;
}

/// Writes pixels p .. p + n - 1 (consecutive in a row) as writeMissPixel writes each, without
/// counting them. One loop per buffer, each a few vector stores; a run of 8 (a row of a default
/// tile) has a constant length, so its stores are made in place (a call to memset per buffer
/// and row of 8 pixels took longer than the stores).
inline void writeMissRun(Frame& frame, std::size_t p, std::size_t n, const RenderSettings& settings) {
    const auto fill = [&](std::size_t m) {
        std::uint8_t* flags = frame.flags.data() + p;
        vec4* rgba = frame.rgba.data() + p;
        float* depth = frame.depth.data() + p;
        std::uint32_t* hitId = frame.hitId.data() + p;
        const vec4 background = settings.background;
        for (std::size_t i = 0; i < m; ++i) flags[i] = Frame::kTraced;
        for (std::size_t i = 0; i < m; ++i) rgba[i] = background;
        for (std::size_t i = 0; i < m; ++i) depth[i] = std::numeric_limits<float>::infinity();
        for (std::size_t i = 0; i < m; ++i) hitId[i] = kNoHit;
    };
    if (n == 8)
        fill(8);
    else
        fill(n);
}

/// The colours of the plain voxel hits a thread shaded last, in a small direct-mapped table
/// (slot: the voxel's index modulo kSlots; voxels are stored in Morton order, so neighbours take
/// different slots). Without smooth surfaces and shadow rays, shade() of a voxel hit depends on
/// the voxel alone (its normal, colour, height and the frame's light), so nearby pixels that hit
/// the same voxel take the same colour from here.
struct ShadeMemo {
    static constexpr std::size_t kSlots = 512;
    std::array<std::uint32_t, kSlots> voxel;
    std::array<vec4, kSlots> colour;
    ShadeMemo() { voxel.fill(kNoHit); }
    /// shade(hit) for a plain voxel hit.
    vec4 shade(const Shader& shader, const TraversalHit& hit, RenderStats& st) {
        const std::size_t i = hit.voxel % kSlots;
        if (voxel[i] != hit.voxel) {
            voxel[i] = hit.voxel;
            colour[i] = shader.shade(hit, &st.secondaryRays);
        }
        return colour[i];
    }
};

/// Writes every field of pixel (x, y) from its primary ray's hit (or miss): flags, hit id,
/// colour (or the background) and depth, and counts the pixel and the hit; a renderer that
/// writes every pixel this way needs no clear (Frame::reshape). Every ray caster shades
/// through this, so equal hits give equal pixels.
/// The hit goes through surfaceHit first (with `counters` and `cut` for the traversal it may
/// go on with). `memo`: the ShadeMemo of the calling thread's current work (one group of tiles), or none.
inline void writePixelHit(Frame& frame, int x, int y, const TraversalHit& proposed, const Shader& shader,
                          const PixelRays& rays, const dvec3& dir, const RenderSettings& settings, RenderStats& st,
                          TraversalCounters& counters, const LodCut* cut = nullptr, ShadeMemo* memo = nullptr) {
    // Taken by reference when surfaceHit would return it unchanged: a copy of the hit just
    // written field by field stalls on store forwarding, a measurable share of a frame.
    TraversalHit tested;
    const bool retest = surfaceTestApplies(shader.smooth(), proposed);
    if (retest) tested = surfaceHit(shader.smooth(), proposed, rays, x, y, dir, counters, cut);
    const TraversalHit& hit = retest ? tested : proposed;
    if (!hit.hit()) {
        writeMissPixel(frame, x, y, settings, st);
        return;
    }
    const std::size_t p = frame.pixel(x, y);
    ++st.pixels;
    frame.flags[p] = Frame::kTraced;
    ++st.hits;
    frame.hitId[p] = hit.voxel;
    if (memo && !hit.smooth && !hit.nodeHit() && hit.leafShift == 0 && !shader.shadows()) {
        frame.rgba[p] = memo->shade(shader, hit, st);
    } else {
        frame.rgba[p] = shader.shade(hit, &st.secondaryRays);
    }
    frame.depth[p] = shader.distance(rays.world(x, y, dir), hit);
}

constexpr int kPerPixelTile = 32;

/// Renders tile by tile (in parallel); each pixel is traced on its own by `trace`, which maps
/// a ray in octree space to a hit. Counters are kept per tile and summed in tile order. `cut`:
/// the multi-resolution cut `trace` honours, for the shared hit path (surfaceHit).
template <class Trace>
RenderStats renderPerPixel(const std::string& name, const Octree& tree, const Camera& camera,
                           const RenderSettings& settings, Frame& frame, const Trace& trace, const LodCut* cut = nullptr) {
    camera.validate();
    Timer timer;
    frame.reshape(camera.width, camera.height);  // every pixel is written below
    const Shader shader(tree, camera, settings);
    const PixelRays rays(tree, camera);
    const int tilesX = (camera.width + kPerPixelTile - 1) / kPerPixelTile;
    const int tilesY = (camera.height + kPerPixelTile - 1) / kPerPixelTile;
    std::vector<RenderStats> tileStats(std::size_t(tilesX) * tilesY);
    parallelFor(tileStats.size(), settings.threads, [&](std::size_t t) {
        RenderStats& st = tileStats[t];
        TraversalCounters counters;
        const int x0 = int(t % std::size_t(tilesX)) * kPerPixelTile, y0 = int(t / std::size_t(tilesX)) * kPerPixelTile;
        const int x1 = std::min(x0 + kPerPixelTile, camera.width), y1 = std::min(y0 + kPerPixelTile, camera.height);
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const dvec3 dir = rays.direction(x, y);
                bool meets = false;
                const TraversalHit hit = trace(rays, x, y, dir, counters, meets);
                if (meets) ++st.rays;
                ++st.raysFull;
                writePixelHit(frame, x, y, hit, shader, rays, dir, settings, st, counters, cut);
            }
        st.nodesVisited = counters.nodes;
    });
    return RenderStats::total(name, tileStats, timer.ms());
}

}  // namespace octrace::detail
