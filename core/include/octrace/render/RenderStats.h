#pragma once
/// @file RenderStats.h
#include <cstdint>
#include <string>

namespace octrace {

/// Counters every renderer fills (summed over threads).
struct RenderStats {
    std::string renderer;
    std::uint64_t pixels = 0;
    std::uint64_t rays = 0;           ///< primary rays that meet the scene cube
    std::uint64_t hits = 0;           ///< rays that found a voxel
    std::uint64_t nodesVisited = 0;   ///< inner nodes whose state was evaluated
    double renderMs = 0.0;
    void add(const RenderStats& o) {
        pixels += o.pixels;
        rays += o.rays;
        hits += o.hits;
        nodesVisited += o.nodesVisited;
    }
};

}  // namespace octrace
