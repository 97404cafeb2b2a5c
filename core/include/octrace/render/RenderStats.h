#pragma once
/// @file RenderStats.h
#include <cstdint>
#include <string>
#include <vector>

namespace octrace {

/// Counters every renderer fills (summed over threads).
struct RenderStats {
    std::string renderer;
    std::uint64_t pixels = 0;
    std::uint64_t rays = 0;           ///< primary rays that meet the scene cube
    std::uint64_t hits = 0;           ///< rays that found a voxel
    std::uint64_t nodesVisited = 0;   ///< inner nodes whose state was evaluated
    // Coherent renderers:
    std::uint64_t raysFull = 0;        ///< pixels traced from the root (supporting rays and others)
    std::uint64_t raysCommonPath = 0;  ///< pixels started from the branch node of two neighbours
    std::uint64_t fallbacks = 0;       ///< of those, retraced from the root
    std::uint64_t raysCertified = 0;   ///< exact variants: started at the branch node, the start proven safe
    std::uint64_t statesDeferred = 0;  ///< exact variants: path nodes whose state byte was never needed
    std::uint64_t colourFilled = 0;    ///< pixels filled by colour coherence, not traced
    std::uint64_t missFilled = 0;      ///< pixels taken as background by miss coherence (exact variants: proven)
    // Direct renderers (they trace no rays: rays = 0):
    std::uint64_t voxelsSplatted = 0;  ///< voxel footprints drawn, counted once per screen tile they cover
    // Sphere scenes (object octree):
    std::uint64_t intersections = 0;   ///< ray-sphere tests of the primary rays (beam on voxels: exact ray-leaf tests)
    std::uint64_t secondaryRays = 0;   ///< shadow, reflected and transmitted rays (Samet)
    std::uint64_t beams = 0;           ///< beam renderer: beams (node, screen rectangle) processed
    double renderMs = 0.0;
    void add(const RenderStats& o) {
        pixels += o.pixels;
        rays += o.rays;
        hits += o.hits;
        nodesVisited += o.nodesVisited;
        raysFull += o.raysFull;
        raysCommonPath += o.raysCommonPath;
        fallbacks += o.fallbacks;
        raysCertified += o.raysCertified;
        statesDeferred += o.statesDeferred;
        colourFilled += o.colourFilled;
        missFilled += o.missFilled;
        voxelsSplatted += o.voxelsSplatted;
        intersections += o.intersections;
        secondaryRays += o.secondaryRays;
        beams += o.beams;
    }
    /// The sum of per-tile (or per-thread) counters in their order, named and timed.
    static RenderStats total(const std::string& renderer, const std::vector<RenderStats>& parts, double renderMs) {
        RenderStats t;
        t.renderer = renderer;
        for (const auto& p : parts) t.add(p);
        t.renderMs = renderMs;
        return t;
    }
};

}  // namespace octrace
