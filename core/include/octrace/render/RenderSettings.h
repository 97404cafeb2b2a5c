#pragma once
/// @file RenderSettings.h
#include "octrace/build/ScalarField.h"
#include "octrace/util/Math.h"

#include <atomic>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace octrace {

/// The coherence of the discrete ray casters (paper A, 5.3; CoherentRenderers.cpp).
struct CoherenceSettings {
    /// Colour coherence: a pixel between two traced neighbours whose 8-bit sRGB colours differ
    /// by at most colourTolerance in every channel gets their average without being traced.
    /// Approximate by design. The renderer names with +colour (area+colour, ...) are the
    /// renderer with this on (resolveRendererName, Renderer.h).
    bool colour = false;
    float colourTolerance = 3.0f;  ///< in 8-bit sRGB units (0..255)
    /// Colour coherence also between two background pixels (the middle one is then taken as
    /// background untraced); off: only between two surface pixels.
    bool colourFillsBackground = false;
    /// Trajectory coherence (linear, area and their exact variants): a common-path ray starts
    /// this many levels above the branch node of its two partners (0 = paper A: at the branch
    /// node; at the octree's depth or more: from the root). Each level up makes the approximate
    /// variants differ from full traversal on fewer pixels and costs speed; the exact variants
    /// stay exact at any value.
    int branchUp = 0;
    /// Miss coherence (the approximate linear and area variants): a common-path pixel whose two
    /// partners both found nothing is taken as background without being traced, as paper A's
    /// colour coherence does between two background pixels. Approximate in the same way as the
    /// start at the branch node: what lies between two missing rays and neither of them meets
    /// is not seen. Off: such a pixel is traced from the root. The exact variants ignore it:
    /// they take such a pixel as a miss only when their tile frontier proves it, always.
    bool miss = true;
};

/// Multi-resolution (Lod.h; needs Octree::computeSummaries): stop descending at a node whose
/// projected size is below lodPixels pixels (0 = exact), and at level `level` at the latest
/// (< 0 = down to the voxels). Read by full, reference and the direct renderers.
struct DetailSettings {
    double lodPixels = 0.0;
    int level = -1;
    /// Whether a cut is asked of an octree of this depth.
    bool active(int depth) const { return lodPixels > 0.0 || (level >= 0 && level < depth); }
};

/// Sphere scenes (object octree, SphereRenderers.cpp).
struct SphereShading {
    /// Rays per pixel on a regular sqrt(samples) x sqrt(samples) grid (1, 4, 9, 16, ...: a
    /// square), averaged.
    int samples = 1;
    /// Whitted depth: reflected / transmitted rays spawned after a primary hit, at most this
    /// many deep (0 = local shading only).
    int bounces = 2;
};

/// How a boundary voxel is drawn (render/SmoothSurface.h): as its box (Voxel: the papers'
/// renderers and every octree without corner values), or where the camera ray crosses the
/// trilinear interpolant of the field's values at the voxel's corners (Smooth), shaded by the
/// interpolant's gradient there; a ray that passes a boundary voxel without crossing goes on.
enum class SurfaceMode : std::uint8_t { Voxel = 0, Smooth = 1 };

/// The settings of one frame. The shared part (threads, colours, light, background, shadows)
/// is read by every renderer; each group after it by the renderers whose traits say so.
struct RenderSettings {
    int threads = 0;                       ///< 0 = all cores; 1 = serial
    vec4 background{1.0f, 1.0f, 1.0f, 1.0f};  ///< linear RGBA of pixels that miss
    vec3 colour{0.85f, 0.62f, 0.35f};      ///< surface albedo (linear RGB)
    dvec3 lightCamera{0.4, 0.6, 1.0};      ///< direction towards the light, camera space (normalised on use)
    float ambient = 0.15f;
    float diffuse = 0.85f;
    /// Shade voxels by their baked light (Octree::baked(), lighting/Bake.h) when the octree has
    /// it: albedo x baked / 255, no normal decoded; else (and for inner nodes drawn whole by
    /// multi-resolution) two-sided Lambert from the normal and lightCamera.
    bool baked = true;
    /// Colour map (Shading.h colormapNames); empty: the uniform `colour`. With
    /// Octree::voxelValues() and no `window` it colours by the values, else by height.
    std::string colormap;
    /// What is mapped onto the colour map's ends: voxel values when the surface is coloured by
    /// its values; heights in world z when it is coloured by height (the model turns the
    /// user's `colour_range`, in the figure's units, into world z). NaN: the lowest / highest
    /// value of the surface's voxels, or the bottom / top of its occupied cell layers.
    float colourMin = std::numeric_limits<float>::quiet_NaN();
    float colourMax = std::numeric_limits<float>::quiet_NaN();
    vec3 maskedColour{0.319f, 0.319f, 0.319f};  ///< linear RGB (sRGB 0.6 grey) of voxels whose value is NaN (masked)
    vec3 floorColour{0.263f, 0.214f, 0.171f};  ///< linear RGB (sRGB 0.55,0.5,0.45) of VoxelMaterial::Floor voxels
    /// Use the octree's per-voxel colours (Octree::colours()) when it has them and no colour
    /// map is set; false: the uniform colour.
    bool voxelColours = true;
    /// When valid, and the octree has voxel values (Octree::voxelValues()), each voxel is grey
    /// by the window applied to its value (instead of `colour` or the colour map);
    /// `invertedGrey`: low values bright (DICOM MONOCHROME1).
    ValueWindow window;
    bool invertedGrey = false;
    /// What the discrete ray casters read (RendererTraits::colourCoherence, trajectoryCoherence,
    /// missCoherence); the other renderers ignore it.
    CoherenceSettings coherence;
    /// The tile renderer's tile side in pixels (its exact pre-pass bounds each tile's rays).
    int tileSize = 8;
    /// What the multi-resolution renderers read (RendererTraits::levelOfDetail); the others
    /// throw UsageError when asked for a cut.
    DetailSettings detail;
    /// What the sphere tracers read (RendererTraits::drawsSpheres: Renderer::renderSpheres).
    SphereShading spheres;
    /// Shadow rays towards the (directional) light. Unset: the scene's default, on for sphere
    /// scenes (Whitted shading, SphereRenderers.cpp) and off for voxel octrees, where each
    /// shaded pixel would cost one more traversal and baked light (lighting/Bake.h) already has
    /// shadows. Voxel octrees: only with dynamic shading (not baked); a voxel the light does
    /// not reach gets the ambient term only (Shader::shade); inner nodes drawn whole by
    /// multi-resolution are not shadowed.
    std::optional<bool> shadows;
    /// Read by every voxel renderer, through the shared hit path (SmoothSurface.h). Smooth on an
    /// octree without corner values (Octree::corners()) draws voxels.
    SurfaceMode surface = SurfaceMode::Voxel;
    /// Not an option: when set and it becomes true, the tile renderer stops at its next band of
    /// background rows or group of tiles and leaves the rest of the frame unwritten (the caller throws the frame away:
    /// the studio, when a newer frame replaces the one being drawn). The other renderers run
    /// to the end.
    const std::atomic<bool>* cancel = nullptr;
};

}  // namespace octrace
