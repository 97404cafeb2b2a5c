#pragma once
/// @file Render.h
/// The pipeline's last steps: the view, the render settings and one frame, from a built surface
/// (Surface.h). What `octrace render`, the studio and (next) Python share, so that each front
/// end only fills a RenderSpec from its own words (argv, widgets, keyword arguments).
#include "octrace/model/OptionTable.h"
#include "octrace/model/Stats.h"
#include "octrace/model/Surface.h"

#include "octrace/io/Figure.h"
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Frame.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/render/RenderStats.h"
#include "octrace/util/Math.h"

#include <optional>
#include <functional>
#include <string>

namespace octrace::model {

/// The coherence settings at the options table's defaults (`colour_tolerance`, `branch_up`,
/// `miss_coherence`; colour coherence off).
CoherenceSettings tableCoherence();
/// The sphere shading at the options table's defaults (`samples`, `bounces`).
SphereShading tableSphereShading();

/// How a frame of a surface is drawn, beyond what the surface says (its colours and lighting,
/// SurfaceSpec): the renderer, the view and the renderer's own settings. Defaults from the
/// options table.
struct RenderSpec {
    /// `renderer`: a name or an alias such as area+colour (resolveRendererName, Renderer.h).
    std::string renderer = opt::renderer.defaultText;
    // The view: image size, camera (unset: framing the surface), projection.
    int width = int(opt::width.defaultValue), height = int(opt::height.defaultValue);
    std::optional<dvec3> cameraPos, lookAt, up;
    double fov = opt::fov.defaultValue;   ///< `fov`, degrees
    bool ortho = false;                   ///< `projection` ortho
    std::optional<double> orthoHeight;    ///< `ortho_height`; unset: framing the surface
    /// sRGB and alpha as a user gives it; unset: contrastingBackground of the surface.
    std::optional<vec4> background;
    std::optional<dvec3> light;               ///< towards the light, camera space; unset: RenderSettings'
    // What only some renderers read (their traits say which).
    CoherenceSettings coherence = tableCoherence();
    DetailSettings detail;  ///< `lod`, `level`
    int tileSize = int(opt::tileSize.defaultValue);  ///< `tile_size`
    SphereShading spheres = tableSphereShading();
};

/// The checks of a voxel render before any work, for every front end: `ortho_height` without
/// an orthographic projection, `level` deeper than the surface's `depth`, colour coherence for
/// a renderer that does not fill by colour, `lod` or `level` for `spec.renderer` or `baseline`
/// (a second renderer, "" none) without a multi-resolution mode. @returns whether the frame
/// is multi-resolution. @throws UsageError naming the settings by their keys.
bool checkRenderSpec(const SurfaceSpec& surface, const RenderSpec& spec, const std::string& baseline = "");

/// Where the default camera looks at a surface from (up is +z in every case): a geographic field
/// north up, from the south and 35 degrees above; a patient volume (LPS) from the front, the
/// anterior view with superior up and the patient's right on the image's left (radiology's
/// convention), or, when the volume is a thin left-right slab (a few sagittal slices, whose
/// anterior view is an edge), from the patient's left, anterior on the image's left (the
/// sagittal convention); anything else from the south-east and above (Camera::obliqueDirection).
enum class SceneView { Oblique, NorthUp, Anterior, Lateral };
/// The view of a field: NorthUp for a geographic grid; for a patient volume Lateral when its
/// grid's left-right extent is under a quarter of its largest, else Anterior; else Oblique.
SceneView sceneView(const ScalarField& field);
/// The direction from the look-at point towards the default camera of `view`.
dvec3 viewDirection(SceneView view);

/// The camera of `spec`: Camera::fit of `bounds` (the surface's box) seen as `view` says, at
/// the spec's size and field of view, then the spec's look-at point, up vector and position
/// over it (a look-at point alone keeps the framing's offset from its look-at point); an
/// orthographic view is framed to the box, its window height replaced by `orthoHeight` when
/// given. Validated.
Camera frameCamera(const RenderSpec& spec, const Box3& bounds, SceneView view = SceneView::Oblique);

/// The background that contrasts most with the surface drawn with `settings` (its colours):
/// white, or ParaView's slate (sRGB 0.32, 0.34, 0.43) behind a light surface, whichever has the
/// larger contrast ratio (WCAG's (L1 + 0.05) / (L2 + 0.05)) with the mean relative luminance of
/// the boundary voxels' albedo (Albedo, Shading.h). Linear RGBA, opaque.
vec4 contrastingBackground(const Octree& tree, const RenderSettings& settings);
/// Whether two settings colour a surface alike: the settings Albedo (Shading.h) reads, which are
/// all contrastingBackground depends on besides the tree.
bool sameColouring(const RenderSettings& a, const RenderSettings& b);
/// Where renderSettings takes the contrasting background from: contrastingBackground, or a
/// caller's memo of it (the studio asks on every camera move; the answer is a pass over every
/// boundary voxel).
using BackgroundSource = std::function<vec4(const Octree& tree, const RenderSettings& settings)>;

/// The render settings of a surface built from `surfaceSpec` (its colours, display window and
/// lighting: applyColour, applyLighting) drawn by `spec` (background, else the contrasting one; light, threads from the
/// surface spec, coherence, detail, sphere shading). The renderer's alias is not applied here:
/// renderFrame does it, so that one RenderSettings serves a main and a baseline renderer.
RenderSettings renderSettings(const SurfaceSpec& surfaceSpec, const Surface& surface, const RenderSpec& spec,
                              const BackgroundSource& background = {});

/// One frame of `tree` with the renderer named `renderer` (a name or an alias, whose setting is
/// applied over `settings`). Throws UsageError for an unknown renderer or one that does not
/// draw voxel octrees.
RenderStats renderFrame(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                        const std::string& renderer, Frame& frame);

/// A frame's figures beyond RenderStats, for frameStats.
struct FrameRecord {
    std::string input;              ///< as given
    const Surface* surface = nullptr;  ///< its field, iso, window, build and bake reports, octree
    const Camera* camera = nullptr;
    const RenderSettings* settings = nullptr;  ///< as given to the renderer, before its alias
    const RenderStats* stats = nullptr;        ///< the frame's (the fastest of repeated ones)
    bool tracesRays = true;         ///< the renderer's trait: us_per_ray is null when it does not
    bool colourCoherence = false;   ///< on for this frame (a setting or a +colour name)
    int threads = 1;                ///< threads used (0 resolved)
    Box3 bounds;                    ///< what the camera frames: the surface's box
    std::optional<io::FigureLayout> figure;
    /// Repeated renders (`repeat`) and a `baseline` renderer alternating with it.
    int repeat = 1;
    double renderMsMedian = 0.0;
    std::string baseline;           ///< as given; empty: none
    double baselineMs = 0.0;
    std::uint64_t baselineDifferingPixels = 0;
    std::uint64_t peakRssAfterBuild = 0;
    bool multiResolution = false;   ///< a cut was asked for (`lod`, `level`): say it
};

/// The record of a frame of `surface` that `renderer` (a name or an alias) drew with
/// `settings` from `camera`: the pointers, the renderer's traits (rays traced, colour coherence
/// by a setting or an alias), the threads used (settings.threads, 0 resolved), what the camera
/// frames. The caller adds the figure, repeats and multi-resolution.
FrameRecord frameRecord(const std::string& input, const Surface& surface, const Camera& camera, const RenderSettings& settings,
                        const RenderStats& stats, const std::string& renderer, const Box3& bounds);

/// The stats of a voxel frame, in the order and with the keys of docs/user/cli.md (`octrace
/// render --stats`): what was drawn, the timings, the renderer's counters, the octree, the
/// view, the multi-resolution cut.
Stats frameStats(const FrameRecord& r);
/// The view's keys (camera_pos, look_at, up, projection, fov or ortho_height, the surface's
/// bounds), shared by voxel and sphere frames.
void addCameraStats(Stats& s, const Camera& camera, const Box3& bounds);
/// The `repeat` and `baseline` keys, shared by voxel and sphere frames.
void addRepeatStats(Stats& s, const FrameRecord& r);
/// "x,y,z" at 10 significant digits, as the stats give a vector.
std::string vectorText(const dvec3& v);

}  // namespace octrace::model
