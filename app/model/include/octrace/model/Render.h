#pragma once
/// @file Render.h
/// The pipeline's last steps: the view, the render settings and one frame, from a built surface
/// (Surface.h). What `octrace render`, the studio and (next) Python share, so that each front
/// end only fills a RenderSpec from its own words (argv, widgets, keyword arguments).
#include "octrace/model/OptionTable.h"
#include "octrace/model/Surface.h"

#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Frame.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/render/RenderStats.h"
#include "octrace/util/Math.h"

#include <optional>
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
    vec4 background{1.0f, 1.0f, 1.0f, 1.0f};  ///< sRGB and alpha as a user gives it
    std::optional<dvec3> light;               ///< towards the light, camera space; unset: RenderSettings'
    // What only some renderers read (their traits say which).
    CoherenceSettings coherence = tableCoherence();
    DetailSettings detail;  ///< `lod`, `level`
    SphereShading spheres = tableSphereShading();
};

/// The camera of `spec`: Camera::framing of `bounds` (the surface's box) at the spec's size and
/// field of view, then the spec's look-at point, up vector and position over it (a look-at
/// point alone keeps the framing's offset from the box's centre); an orthographic view is
/// framed to the box, its window height replaced by `orthoHeight` when given. Validated.
Camera frameCamera(const RenderSpec& spec, const Box3& bounds);

/// The render settings of a surface built from `surfaceSpec` (its colours, display window and
/// lighting: applyColour, applyLighting) drawn by `spec` (background, light, threads from the
/// surface spec, coherence, detail, sphere shading). The renderer's alias is not applied here:
/// renderFrame does it, so that one RenderSettings serves a main and a baseline renderer.
RenderSettings renderSettings(const SurfaceSpec& surfaceSpec, const Surface& surface, const RenderSpec& spec);

/// One frame of `tree` with the renderer named `renderer` (a name or an alias, whose setting is
/// applied over `settings`). Throws UsageError for an unknown renderer or one that does not
/// draw voxel octrees.
RenderStats renderFrame(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                        const std::string& renderer, Frame& frame);

}  // namespace octrace::model
