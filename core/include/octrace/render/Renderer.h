#pragma once
/// @file Renderer.h
/// The interface every renderer shares, so that the CLI, the Qt application and the
/// benchmarks can swap them and compare images pixel by pixel.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Frame.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/render/RenderStats.h"

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
    /// Renders into `frame` (resized to the camera's size). Deterministic: the result does not
    /// depend on settings.threads. Thread-safe for distinct frames.
    virtual RenderStats render(const Octree& octree, const Camera& camera, const RenderSettings& settings,
                               Frame& frame) const = 0;
};

/// Names accepted by makeRenderer, in the order the help text lists them.
std::vector<std::string> rendererNames();
/// Throws UsageError for an unknown name.
std::unique_ptr<Renderer> makeRenderer(const std::string& name);

}  // namespace octrace
