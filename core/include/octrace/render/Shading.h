#pragma once
/// @file Shading.h
/// Shading shared by every renderer, so that two renderers that find the same voxel produce
/// the same pixel bytes.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/RenderSettings.h"

#include <string>
#include <vector>

namespace octrace {

/// Named colour maps for --colormap (linear RGB, t in [0,1]). With a colour map the surface is
/// coloured by height: t runs from the lowest to the highest boundary voxel.
std::vector<std::string> colormapNames();
/// Throws UsageError for an unknown name.
vec3 colormap(const std::string& name, float t);

/// The surface's colour before lighting, linear RGB: with a display window (and voxel values in
/// the octree) the window's grey of the voxel's value; else with a colour map the map's colour
/// for the height, from the lowest to the highest boundary voxel; else the voxel's own colour
/// when the octree has per-voxel colours (Octree::colours) and RenderSettings::voxelColours is
/// set; else RenderSettings::colour. Shared
/// by Shader and the surfel export (Surfels.h), so that both colour a voxel alike.
/// Thread-safe once constructed.
class Albedo {
public:
    /// Throws UsageError for an unknown colour map name.
    Albedo(const Octree& tree, const RenderSettings& settings);
    /// `voxel`: the boundary voxel (for a node, its summary's firstVoxel); `zCells`: height in
    /// cell space (a voxel's centre is at cell.z + 0.5; a node's is its summary's meanZ).
    vec3 at(std::uint32_t voxel, float zCells) const;

private:
    vec3 colour_;
    const std::vector<std::uint32_t>* colours_ = nullptr;  // the octree's per-voxel colours, or null
    float linear_[256];  // sRGB byte -> linear
    const std::vector<float>* values_ = nullptr;  // with a window: the octree's voxel values
    ValueWindow window_;
    bool inverted_ = false;
    std::string colormap_;   // empty: uniform colour_
    int zLo_ = 0, zHi_ = 0;  // occupied cell range along z, for the colour map
};

/// Per-frame constants: light in world space, colour settings.
class Shader {
public:
    Shader(const Octree& tree, const Camera& camera, const RenderSettings& settings);
    /// Two-sided Lambert: ambient + diffuse * |n . l|, times the surface colour.
    vec4 shade(std::uint32_t voxel, const ivec3& cell) const;
    /// Distance from the camera along the (unit) ray to where it enters the voxel's box.
    float distance(const Ray& ray, const ivec3& cell) const;
    /// An inner node drawn whole (multi-resolution): its summary's normal and mean height.
    vec4 shadeNode(std::uint32_t node) const;
    /// Either kind of hit.
    vec4 shade(const TraversalHit& hit) const {
        return hit.nodeHit() ? shadeNode(hit.node) : shade(hit.voxel, hit.cell);
    }
    float distance(const Ray& ray, const TraversalHit& hit) const;

private:
    vec4 shadeNormal(vec3 n, std::uint32_t voxel, float zCells) const;
    float distanceToBox(const Ray& ray, const Box3& b) const;
    const Octree& tree_;
    const RenderSettings& settings_;
    vec3 light_;
    Albedo albedo_;
};

}  // namespace octrace
