#pragma once
/// @file Renderer.h
/// The interface every renderer shares, so that the CLI, the Qt application and the
/// benchmarks can swap them and compare images pixel by pixel.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Frame.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/render/RenderStats.h"
#include "octrace/scene/ObjectOctree.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace octrace {

/// What a renderer draws and which parts of RenderSettings beyond the shared ones (camera,
/// colours, light, background, threads) it reads. Each renderer declares it once, in traits();
/// the CLI's warnings and help, the studio's enabled controls and the options table's
/// `renderers` field read it through the accessors of Renderer.
struct RendererTraits {
    /// Rays per pixel; false for the direct (object-order) renderers: RenderStats::rays is 0
    /// and us-per-ray figures do not apply.
    bool tracesRays = true;
    bool drawsVoxels = true;   ///< render() draws the voxel octree
    bool drawsSpheres = false; ///< renderSpheres() draws sphere scenes (RenderSettings::spheres, shadows)
    /// RenderSettings::detail (Lod.h); the others throw UsageError when asked for a cut.
    bool levelOfDetail = true;
    /// CoherenceSettings::colour, colourTolerance, colourFillsBackground (the discrete ray
    /// casters); the CLI refuses `colour_coherence` for the others.
    bool colourCoherence = false;
    /// CoherenceSettings::branchUp (trajectory coherence: linear and area and their variants).
    bool trajectoryCoherence = false;
    /// CoherenceSettings::miss (the approximate linear and area).
    bool missCoherence = false;
    /// One of the papers' renderers (full, linear, area and their variants, direct, samet,
    /// beam): the front ends draw voxels with it unless smooth surfaces are asked for
    /// (RenderSettings::surface), so that the reproductions' images and tables stay as they were.
    bool paper = false;
    /// RenderSettings::tileSize (the tile renderer).
    bool tiled = false;
};

class Renderer {
public:
    virtual ~Renderer() = default;
    virtual std::string name() const = 0;
    /// What it draws and reads (the defaults: a ray caster of voxels with multi-resolution).
    virtual RendererTraits traits() const { return {}; }
    // The traits one by one, for code that names a capability (e.g. voxelRenderersThat).
    bool tracesRays() const { return traits().tracesRays; }
    bool multiResolution() const { return traits().levelOfDetail; }
    bool colourCoherence() const { return traits().colourCoherence; }
    bool trajectoryCoherence() const { return traits().trajectoryCoherence; }
    bool missCoherence() const { return traits().missCoherence; }
    bool paperRenderer() const { return traits().paper; }
    bool tiled() const { return traits().tiled; }
    /// Renders into `frame` (resized to the camera's size). Deterministic: the result does not
    /// depend on settings.threads. Thread-safe for distinct frames.
    virtual RenderStats render(const Octree& octree, const Camera& camera, const RenderSettings& settings,
                               Frame& frame) const = 0;
    /// Whether renderSpheres draws sphere scenes (reference, samet, beam).
    bool drawsSpheres() const { return traits().drawsSpheres; }
    /// Whether render() draws the voxel octree (every renderer but the brute-force sphere oracle).
    bool drawsVoxels() const { return traits().drawsVoxels; }
    /// Renders a sphere scene through its object octree: hitId is the sphere index of the
    /// pixel's first sample, depth that sample's distance, rgba the average of the samples
    /// (RenderSettings::samples), shaded with Whitted's rays (bounces, shadows). Deterministic
    /// and thread-safe like render(). Throws UsageError for renderers that do not draw spheres.
    virtual RenderStats renderSpheres(const ObjectOctree& tree, const Camera& camera, const RenderSettings& settings,
                                      Frame& frame) const;
};

/// Progressive rendering for interactive use: a coarse frame first, then finer ones. Renders
/// with each of `lodPasses` (pixels, coarse to fine) and finally exactly, calling
/// onFrame(frame, lodPixels) after each (0 for the exact one); stops early when it returns
/// false. A renderer without multi-resolution renders only the exact frame. Needs
/// Octree::computeSummaries. Returns the number of frames delivered.
int renderProgressive(const Renderer& renderer, const Octree& octree, const Camera& camera,
                      const RenderSettings& settings, Frame& frame,
                      const std::function<bool(const Frame&, double lodPixels)>& onFrame,
                      const std::vector<double>& lodPasses = {8.0, 4.0, 2.0});

/// The side s of antialiasing's s x s grid of rays per pixel: `samples` must be a square number
/// from 1 to 256 (RenderSettings::spheres.samples); throws UsageError otherwise.
int samplesPerSide(int samples);
/// Renders the voxel octree with RenderSettings::spheres.samples rays per pixel (s x s, on the
/// grid of the sphere tracers: sample (a, b) of a pixel passes at ((a + 0.5) / s, (b + 0.5) / s)
/// of it): `renderer` draws the frame once per sample with Camera::sampleOffset, each draw
/// exact as its renderer is, and the colours are averaged with their alpha (premultiplied), so
/// an edge against a transparent background is not darkened. Depth, hitId and flags are the
/// first sample's (the pixel's top-left one), as renderSpheres gives them. The stats sum the
/// samples' counters and time (pixels counted once). One sample is renderer.render() itself.
RenderStats renderAntialiased(const Renderer& renderer, const Octree& octree, const Camera& camera,
                              const RenderSettings& settings, Frame& frame);
/// Primary rays of a sphere scene tested against every sphere, no octree (the oracle that
/// --verify and the tests judge the octree tracers by; O(spheres) per ray). Draws spheres only.
std::unique_ptr<Renderer> makeBruteForceSphereRenderer();

/// Names accepted by makeRenderer, in the order the help text lists them.
std::vector<std::string> rendererNames();
/// The renderer names as menus list them: rendererNames() with area+colour (paper A's area
/// with colour coherence, an alias: resolveRendererName) after area.
std::vector<std::string> rendererMenuNames();

/// A renderer's name as the front ends take it (CLI --renderer and --baseline, sessions, the
/// studio's menus, benchmark scripts): a name of rendererNames(), or an alias that is a
/// renderer and a setting. `X+colour` (and `X+color`) for a discrete ray caster X is X with
/// CoherenceSettings::colour on, so paper A's area+colour is `area` with colour coherence.
/// The setting, not the name, selects the behaviour; the renderer reports the alias back in
/// RenderStats::renderer when the setting is on.
struct RendererName {
    std::string renderer;          ///< a name of rendererNames(), for makeRenderer
    bool colourCoherence = false;  ///< the name had +colour
    /// Turns on what the name says in `settings` (leaves it as it is otherwise).
    void applyTo(RenderSettings& settings) const;
};
/// Splits a name or alias; throws UsageError for an unknown name (or +colour after a renderer
/// without colour coherence).
RendererName resolveRendererName(const std::string& name);
/// The renderers that draw voxels and pass `honours` (e.g. &Renderer::multiResolution), as
/// "a, b or c": for help texts and errors.
std::string voxelRenderersThat(bool (Renderer::*honours)() const);
/// The renderer of a name of rendererNames(). Throws UsageError for an unknown name and for an
/// alias (resolveRendererName first, so that its setting is not lost).
std::unique_ptr<Renderer> makeRenderer(const std::string& name);

}  // namespace octrace
