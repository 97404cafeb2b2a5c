#pragma once
/// @file Surfels.h
/// The shell as surfels (surface elements: oriented discs) for hardware splatting, e.g. in an
/// OpenGL view, and for point-cloud export (io/PlyWriter.h).
///
/// One surfel per boundary voxel, or per non-empty node of a coarser level for previews:
///  - position: the centre of the voxel's (node's) box, world units;
///  - normal: the voxel's decoded normal (the node summary's average normal), unit length;
///  - radius: half the diagonal of the box, sqrt(3)/2 times its edge. The disc of that radius
///    around the centre, perpendicular to the normal, covers the box's projection onto the
///    disc's plane whatever the normal, so neighbouring splats leave no holes; it depends on
///    the level only;
///  - colour: the albedo the renderers use for that voxel (Albedo in Shading.h: uniform colour
///    or colour map by height), without lighting (a splatting view lights the normals itself),
///    as 8-bit sRGB (linearToSrgb8, as in the PNG files), alpha 255.
#include "octrace/octree/Octree.h"
#include "octrace/render/RenderSettings.h"

#include <array>
#include <cstdint>
#include <vector>

namespace octrace {

/// One oriented disc. 32 bytes, no padding: an array of them can be uploaded as an OpenGL
/// vertex buffer as is (offsets 0, 12, 24, 28; the colour as normalized unsigned bytes).
struct Surfel {
    vec3 position{0.0f};                 ///< world units
    vec3 normal{0.0f, 0.0f, 1.0f};       ///< unit
    float radius = 0.0f;                 ///< world units
    std::array<std::uint8_t, 4> rgba{};  ///< 8-bit sRGB colour, straight alpha
};
static_assert(sizeof(Surfel) == 32, "Surfel is uploaded to the GPU as is");

/// Radius of the surfel of an octant with world edge length `side`: half its diagonal.
float surfelRadius(double side);

/// The surfels of `tree`, in the depth-first order of Octree::forEachAtLevel (the order of
/// forEachVoxel at the voxel level), so the result is the same for any thread count.
///
/// `level` < 0 or == tree.depth: one surfel per boundary voxel. 0 <= level < depth: one per
/// node at that level with boundary voxels below (needs Octree::computeSummaries()).
/// From `settings` only the colour (colour, colormap) and `threads` are used.
/// @throws UsageError for a level deeper than the tree, a coarser level without summaries, or
///         an unknown colour map.
/// Thread-safe: reads the tree only; the caller owns the result.
std::vector<Surfel> extractSurfels(const Octree& tree, const RenderSettings& settings, int level = -1);

}  // namespace octrace
