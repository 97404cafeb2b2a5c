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

class Renderer {
public:
    virtual ~Renderer() = default;
    virtual std::string name() const = 0;
    /// False for the direct (object-order) renderers: they trace no rays, RenderStats::rays is
    /// 0 and us-per-ray figures do not apply.
    virtual bool tracesRays() const { return true; }
    /// Whether RenderSettings::lodPixels / level are honoured (Lod.h); the others throw
    /// UsageError when asked for a cut.
    virtual bool multiResolution() const { return true; }
    /// Whether RenderSettings::colourCoherence is honoured (the discrete ray casters); the CLI
    /// refuses the option for the others.
    virtual bool colourCoherence() const { return false; }
    /// Whether it always fills pixels by colour coherence (the +colour variants), so that
    /// RenderSettings::colourTolerance applies without RenderSettings::colourCoherence.
    virtual bool fillsByColour() const { return false; }
    /// Whether RenderSettings::branchUp is honoured (trajectory coherence: linear and area and
    /// their exact and +colour variants).
    virtual bool trajectoryCoherence() const { return false; }
    /// Whether RenderSettings::missCoherence is honoured (the approximate linear and area and
    /// their +colour variants; never the exact ones).
    virtual bool missCoherence() const { return false; }
    /// Renders into `frame` (resized to the camera's size). Deterministic: the result does not
    /// depend on settings.threads. Thread-safe for distinct frames.
    virtual RenderStats render(const Octree& octree, const Camera& camera, const RenderSettings& settings,
                               Frame& frame) const = 0;
    /// Whether renderSpheres draws sphere scenes (reference, samet, beam).
    virtual bool drawsSpheres() const { return false; }
    /// Whether render() draws the voxel octree (every renderer but the brute-force sphere oracle).
    virtual bool drawsVoxels() const { return true; }
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

/// Primary rays of a sphere scene tested against every sphere, no octree (the oracle that
/// --verify and the tests judge the octree tracers by; O(spheres) per ray). Draws spheres only.
std::unique_ptr<Renderer> makeBruteForceSphereRenderer();

/// Names accepted by makeRenderer, in the order the help text lists them.
std::vector<std::string> rendererNames();
/// The renderers that draw voxels and pass `honours` (e.g. &Renderer::multiResolution), as
/// "a, b or c": for help texts and errors.
std::string voxelRenderersThat(bool (Renderer::*honours)() const);
/// Throws UsageError for an unknown name.
std::unique_ptr<Renderer> makeRenderer(const std::string& name);

}  // namespace octrace
