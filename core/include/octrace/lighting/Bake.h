#pragma once
/// @file Bake.h
/// Precomputed diffuse lighting (paper A's first shading mode): per boundary voxel of a shell
/// octree, the light it receives from fixed lights, with hard shadows and ambient occlusion
/// found by shadow rays through the octree itself (the discrete traversal), stored in 8 bits
/// (Octree::baked()). Renderers then shade a voxel by albedo x baked / 255 instead of from its
/// normal and the view's light (RenderSettings::baked).
///
/// For voxel v with unit normal n at centre c, and for each light i (unit direction l_i
/// towards it: fixed for a directional light, towards its position for a point light):
///   light(v) = ambient x AO(v) + diffuse x sum_i intensity_i x visible_i(v) x |n . l_i|
/// clamped to [0, 1] and stored as round(255 x light). Two-sided, as the dynamic shading:
/// visible_i is 1 unless the shadow ray from c (offset by one voxel to the side of n facing
/// the light) meets a boundary voxel before the light. AO(v) is the larger, over the two sides
/// of the surface, of the fraction of `aoRays` directions of that hemisphere (a Fibonacci
/// spiral) whose rays meet no boundary voxel within `aoDistance`. Hits in the voxels next to
/// the ray's own start are stepped over (the surface's own neighbours).
#include "octrace/octree/Octree.h"
#include "octrace/util/Math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace {

struct BakeLight {
    bool point = false;      ///< a point light at `v` (world); else a directional light towards `v`
    dvec3 v{0.3, -0.5, 1.0};
    float intensity = 1.0f;
};

struct BakeOptions {
    std::vector<BakeLight> lights{BakeLight{}};  ///< default: one directional light from above the south-east
    int aoRays = 8;              ///< per hemisphere; 0 = no ambient occlusion (AO = 1)
    double aoDistance = 0.0;     ///< world units; 0 = an eighth of the cube's side
    bool shadows = true;
    float ambient = 0.15f, diffuse = 0.85f;  ///< as RenderSettings' dynamic shading
    int threads = 0;
};

struct BakeReport {
    double bakeMs = 0.0;
    std::uint64_t rays = 0;  ///< shadow and AO rays traced
};

/// Fills tree.baked (one byte per voxel). The tree must be in the shell form (UsageError
/// otherwise). Does not depend on `threads`.
void bakeLighting(Octree& tree, const BakeOptions& options, BakeReport* report = nullptr);

/// "dir:X,Y,Z[,I]" (direction towards the light, world) or "point:X,Y,Z[,I]" (position, world);
/// I the intensity (default 1). UsageError naming the problem.
BakeLight parseBakeLight(const std::string& spec);

}  // namespace octrace
