#include "render/traversal/CoherentRenderers.h"
#include "render/direct/DirectRenderer.h"
#include "render/PerPixel.h"
#include "render/traversal/PixelRays.h"
#include "render/traversal/TileRenderer.h"
#include "render/spheres/SphereRenderers.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/Lod.h"
#include "octrace/render/ReferenceTraversal.h"
#include "octrace/render/Renderer.h"
#include "octrace/render/Shading.h"
#include "octrace/render/SmoothSurface.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>

namespace octrace {
namespace {

class ReferenceRenderer final : public Renderer {
public:
    explicit ReferenceRenderer(bool quantized) : quantized_(quantized) {}
    std::string name() const override { return quantized_ ? "reference" : "reference-unquantized"; }
    RenderStats render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                       Frame& frame) const override {
        const LodCut cut(tree, camera, settings.detail.lodPixels, settings.detail.level);
        // Smooth surfaces: the reference's own test (a float64 march, SmoothSurface.h) inside its
        // own traversal, independent of the fast renderers' shared hit path.
        const SmoothSurface smooth(tree, settings);
        return detail::renderPerPixel(name(), tree, camera, settings, frame,
                              [&](const detail::PixelRays& rays, int x, int y, const dvec3& d, TraversalCounters& c, bool& meets) {
                                  QuantizedRay q = rays.quantized(x, y, d);
                                  ReferenceRay r = quantized_ ? referenceRayFromQuantized(q)
                                                              : referenceRayUnquantized(rays.originOS(x, y), d);
                                  SmoothSurface::RayState ray{rays.world(x, y, d)};
                                  const VoxelFilter filter = smooth.filter(ray, true);
                                  TraversalHit hit = traverseReference(tree, r, c, &cut, &filter);
                                  // The unquantized ray can graze a cube face from inside where
                                  // its quantized twin is rounded onto the face (outside): it
                                  // meets the cube when it hits, so that hits <= rays holds.
                                  meets = q.meetsCube || hit.hit();
                                  return hit;
                              },
                              &cut);
    }
    RendererTraits traits() const override {
        RendererTraits t;
        t.drawsSpheres = quantized_;  // the quantized reference also traces the object octree
        return t;
    }
    /// Sphere scenes: the recursive parametric traversal of the object octree.
    RenderStats renderSpheres(const ObjectOctree& tree, const Camera& camera, const RenderSettings& settings,
                              Frame& frame) const override {
        if (!quantized_) return Renderer::renderSpheres(tree, camera, settings, frame);
        return detail::renderSphereScene(detail::SphereTracer::Reference, name(), tree, camera, settings, frame);
    }

private:
    bool quantized_;
};

}  // namespace

int renderProgressive(const Renderer& renderer, const Octree& tree, const Camera& camera, const RenderSettings& settings,
                      Frame& frame, const std::function<bool(const Frame&, double)>& onFrame,
                      const std::vector<double>& lodPasses) {
    int delivered = 0;
    RenderSettings s = settings;
    if (renderer.multiResolution()) {
        for (double pixels : lodPasses) {
            if (!(pixels > 0.0)) continue;
            s.detail.lodPixels = pixels;
            renderer.render(tree, camera, s, frame);
            ++delivered;
            if (!onFrame(frame, pixels)) return delivered;
        }
    }
    s.detail.lodPixels = 0.0;
    s.detail.level = -1;
    renderer.render(tree, camera, s, frame);
    onFrame(frame, 0.0);
    return delivered + 1;
}

std::vector<std::string> rendererNames() {
    return {"full", "tile", "linear", "area", "linear-exact", "area-exact", "reference", "reference-unquantized", "direct", "direct-f2b", "samet", "beam"};
}

std::vector<std::string> rendererMenuNames() {
    std::vector<std::string> names = rendererNames();
    names.insert(std::find(names.begin(), names.end(), "area") + 1, "area+colour");
    return names;
}

void RendererName::applyTo(RenderSettings& settings) const {
    if (colourCoherence) settings.coherence.colour = true;
}

RendererName resolveRendererName(const std::string& nameIn) {
    RendererName r{nameIn, false};
    for (const char* suffix : {"+colour", "+color"}) {
        const std::string sfx(suffix);
        if (r.renderer.size() > sfx.size() && r.renderer.compare(r.renderer.size() - sfx.size(), sfx.size(), sfx) == 0) {
            r.renderer.erase(r.renderer.size() - sfx.size());
            r.colourCoherence = true;
            break;
        }
    }
    const std::vector<std::string> names = rendererNames();
    const bool known = std::find(names.begin(), names.end(), r.renderer) != names.end();
    if (known && (!r.colourCoherence || makeRenderer(r.renderer)->colourCoherence())) return r;
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw UsageError("unknown renderer '" + nameIn + "' (choose one of: " + list + "; " +
                     voxelRenderersThat(&Renderer::colourCoherence) + " take the suffix +colour for colour coherence)");
}

std::string voxelRenderersThat(bool (Renderer::*honours)() const) {
    std::vector<std::string> names;
    for (const std::string& n : rendererNames()) {
        const auto r = makeRenderer(n);
        if (r->drawsVoxels() && ((*r).*honours)()) names.push_back(n);
    }
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
        list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return list;
}

std::unique_ptr<Renderer> makeRenderer(const std::string& name) {
    using detail::DiscreteRenderer;
    if (name == "full") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Full, false);
    if (name == "tile") return std::make_unique<detail::TileRenderer>();
    if (name == "linear") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Linear, false);
    if (name == "area") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Area, false);
    if (name == "linear-exact") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Linear, true);
    if (name == "area-exact") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Area, true);
    if (name == "reference") return std::make_unique<ReferenceRenderer>(true);
    if (name == "reference-unquantized") return std::make_unique<ReferenceRenderer>(false);
    if (name == "direct") return std::make_unique<detail::DirectRenderer>(false);
    if (name == "direct-f2b") return std::make_unique<detail::DirectRenderer>(true);
    if (auto r = detail::makeSphereRenderer(name)) return r;
    // An alias (area+colour) is a renderer and a setting: resolveRendererName splits it, so
    // that the setting is not lost here.
    const RendererName alias = resolveRendererName(name);
    throw UsageError("renderer '" + name + "' is " + alias.renderer + " with colour coherence: resolve it with resolveRendererName");
}

}  // namespace octrace
