#pragma once
// Private to core: shadow and occlusion rays through a shell octree by the discrete traversal,
// shared by the lighting bake (Bake.cpp) and the dynamic shading's shadows (Shading.cpp), so
// that both decide alike what a voxel's own surface is.
#include "octrace/octree/Octree.h"
#include "octrace/util/Math.h"

#include <cstdint>

namespace octrace::detail {

class ShadowTracer {
public:
    explicit ShadowTracer(const Octree& tree);

    /// World distance from `origin` along unit `dir` to the first boundary leaf not next to
    /// the start leaf (cells `start` .. start + 2^startShift - 1, cell space), or +inf. Leaves
    /// within one voxel of the start leaf are the surface's own neighbours: the ray continues
    /// just past them (at most 4 times). `rays` counts the traversals started.
    double firstHit(dvec3 origin, const dvec3& dir, const ivec3& start, int startShift, std::uint64_t& rays) const;

    /// Whether the leaf at `cell` (its lowest voxel cell) of side 2^shift voxels, with unit
    /// normal `n`, sees a directional light along unit `dir` (towards the light): the ray
    /// from its centre, offset by one leaf side to the side of n facing the light, meets no
    /// other boundary leaf. Two-sided like the shading; `n . dir == 0` counts as lit.
    bool seesDirectionalLight(const ivec3& cell, int shift, const dvec3& n, const dvec3& dir, std::uint64_t& rays) const;

private:
    const Octree& t_;
    double toOS_;
};

}  // namespace octrace::detail
