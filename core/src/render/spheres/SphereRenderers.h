#pragma once
// Private to core: the renderers of sphere scenes (object octree). How they work:
// docs/dev/spheres.md.
#include "octrace/render/Renderer.h"

#include <memory>
#include <string>

namespace octrace::detail {

enum class SphereTracer { Reference, Samet, Beam, BruteForce };

/// Renders a sphere scene with the given primary-ray tracer; every tracer shares the ray
/// generation, the shading (Whitted, secondary rays by Samet's method) and the sample
/// averaging, so equal hits give equal pixels.
RenderStats renderSphereScene(SphereTracer tracer, const std::string& name, const ObjectOctree& tree, const Camera& camera,
                              const RenderSettings& settings, Frame& frame);

/// "samet" or "beam"; nullptr for other names.
std::unique_ptr<Renderer> makeSphereRenderer(const std::string& name);

}  // namespace octrace::detail
