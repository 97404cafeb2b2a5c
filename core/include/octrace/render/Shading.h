#pragma once
/// @file Shading.h
/// Shading shared by every renderer, so that two renderers that find the same voxel produce
/// the same pixel bytes.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/render/SmoothSurface.h"

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace octrace {

/// Named colour maps for --colormap (linear RGB, t in [0,1]): viridis, the cmocean maps
/// thermal, haline and speed, grey (cmocean gray; "gray" is accepted too) and coolwarm. The
/// tables and where they come from: scripts/colormaps.py.
std::vector<std::string> colormapNames();
/// Throws UsageError for an unknown name.
vec3 colormap(const std::string& name, float t);
/// A colour map looked up by name once: colormap(name, t) without the look-up per call.
class Colormap {
public:
    /// Throws UsageError for an unknown name.
    explicit Colormap(const std::string& name);
    vec3 operator()(float t) const;

private:
    const vec3* linear_ = nullptr;  // linear RGB at steps_ + 1 equal steps (Shading.cpp, LinearMap)
    std::size_t steps_ = 0;
};
/// The colour map for a variable, by its CF standard_name (sea water temperature: thermal,
/// salinity: haline, speed of sound: speed), else by its name (TEMP, SALT, sound_speed, ...);
/// viridis for anything else.
std::string defaultColormap(const std::string& standardName, const std::string& name);

/// The surface's colour before lighting, linear RGB, per voxel:
///  - VoxelMaterial::Floor voxels: RenderSettings::floorColour;
///  - with Octree::voxelValues() and a display window (RenderSettings::window): the window's
///    grey of the voxel's value;
///  - with Octree::voxelValues(), no window and a colour map: the map's colour for the voxel's
///    value over [colourMin, colourMax] (NaN ends: the surface voxels' own range), maskedColour
///    for NaN;
///  - else with a colour map the map's colour for the height, from the lowest to the highest
///    boundary voxel;
///  - else the voxel's own colour when the octree has per-voxel colours (Octree::colours()) and
///    RenderSettings::voxelColours is set; else RenderSettings::colour.
/// Shared by Shader and the surfel export (Surfels.h), so that both colour a voxel alike.
/// Thread-safe once constructed.
class Albedo {
public:
    /// Throws UsageError for an unknown colour map name.
    Albedo(const Octree& tree, const RenderSettings& settings);
    /// `voxel`: index in tree.voxels (a node drawn whole: its summary's firstVoxel).
    /// `zCells`: height in cell space (a voxel's centre is at cell.z + 0.5; a node's is its
    /// summary's meanZ).
    vec3 at(std::uint32_t voxel, float zCells) const;
    /// Starts fetching what at(voxel, ...) reads of the voxel's own attributes (its material,
    /// colour or value), for a caller that knows the voxel well before it shades it.
    void prefetch(std::uint32_t voxel) const;
    /// Colouring by voxel values with the colour map, over [low(), high()] with colormapName().
    bool byValue() const { return values_ != nullptr && !window_.valid(); }
    float low() const { return lo_; }
    float high() const { return hi_; }
    const std::string& colormapName() const { return colormap_; }
    /// Colouring by height with the colour map: colour 0 at heightLow(), 1 at heightHigh()
    /// (cell space along z): RenderSettings::colourMin/colourMax (world z) when given, else
    /// the bottom of the lowest and the top of the highest occupied cell layer.
    bool byHeight() const { return values_ == nullptr && !colormap_.empty(); }
    float heightLow() const { return hLo_; }
    float heightHigh() const { return hHi_; }

private:
    const Octree& tree_;
    vec3 colour_, masked_, floor_;
    const std::vector<std::uint32_t>* colours_ = nullptr;  // the octree's per-voxel colours, or null
    float linear_[256];  // sRGB byte -> linear
    const std::vector<float>* values_ = nullptr;  // the octree's voxel values (window or colour map)
    ValueWindow window_;
    bool inverted_ = false;
    std::string colormap_;   // empty: uniform colour_
    std::optional<Colormap> map_;  // colormap_ looked up
    float lo_ = 0.0f, hi_ = 1.0f;  // value range
    float hLo_ = 0.0f, hHi_ = 1.0f;  // heights at the colour map's ends (cell space along z)
};

/// Per-frame constants: light in world space, colour settings.
class Shader {
public:
    Shader(const Octree& tree, const Camera& camera, const RenderSettings& settings);
    /// Two-sided Lambert: ambient + diffuse * |n . l|, times the surface colour; or the baked
    /// light times the surface colour (RenderSettings::baked). With RenderSettings::shadows
    /// and dynamic shading, ambient only where the light does not reach the leaf: a shadow ray
    /// by the discrete traversal from the leaf (`cell`, its lowest voxel cell; side
    /// 2^leafShift voxels) towards the light, offset by one leaf side to the light's side of
    /// the normal, as the bake's (lighting/Bake.h). Its traversals are added to `shadowRays`
    /// when given. The colour depends only on the leaf, so renderers that find the same
    /// leaf give the same pixel.
    vec4 shade(std::uint32_t voxel, const ivec3& cell, int leafShift = 0, std::uint64_t* shadowRays = nullptr) const;
    /// Starts fetching what shade() reads of the voxel (its normal or baked light, and its
    /// colour, Albedo::prefetch): a hit found well before it is shaded is then shaded from the
    /// cache. `normal`: false for a hit that brings its own normal (a smooth surface's).
    void prefetch(std::uint32_t voxel, bool normal = true) const;
    /// Distance from the camera along the (unit) ray to where it enters the voxel's box.
    float distance(const Ray& ray, const ivec3& cell) const;
    /// An inner node drawn whole (multi-resolution): its summary's normal and mean height.
    vec4 shadeNode(std::uint32_t node) const;
    /// Any kind of hit; a smooth one (SmoothSurface.h) is lit by its own normal, else as shade().
    vec4 shade(const TraversalHit& hit, std::uint64_t* shadowRays = nullptr) const {
        if (hit.nodeHit()) return shadeNode(hit.node);
        if (hit.smooth) return shadeNormal(hit.voxel, hit.cell, hit.normal, shadowRays, 0, hit.zCells);
        return shade(hit.voxel, hit.cell, hit.leafShift, shadowRays);
    }
    /// The frame's smooth-surface test (RenderSettings::surface), for the shared hit path.
    const SmoothSurface& smooth() const { return smooth_; }
    /// Whether shade() traces shadow rays.
    bool shadows() const { return shadows_; }
    /// Where the ray enters the hit's box, or a smooth hit's own distance.
    float distance(const Ray& ray, const TraversalHit& hit) const;

private:
    /// `zCells`: the height the colour is taken at (colouring by height); NaN: the voxel's centre.
    vec4 shadeNormal(std::uint32_t voxel, const ivec3& cell, vec3 n, std::uint64_t* shadowRays, int leafShift = 0,
                     float zCells = std::numeric_limits<float>::quiet_NaN()) const;
    vec4 shadeLambert(std::uint32_t voxel, float zCells, float lambert) const;
    float distanceToBox(const Ray& ray, const Box3& b) const;
    const Octree& tree_;
    const RenderSettings& settings_;
    vec3 light_;
    Albedo albedo_;
    const std::vector<std::uint8_t>* baked_ = nullptr;  // RenderSettings::baked and the octree has it
    bool shadows_ = false;  // RenderSettings::shadows, dynamic shading of a shell octree
    SmoothSurface smooth_;
};

}  // namespace octrace
