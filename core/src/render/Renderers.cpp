#include "render/traversal/CoherentRenderers.h"
#include "render/direct/DirectRenderer.h"
#include "render/PerPixel.h"
#include "render/traversal/PixelRays.h"
#include "render/spheres/SphereRenderers.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/Lod.h"
#include "octrace/render/ReferenceTraversal.h"
#include "octrace/render/Renderer.h"
#include "octrace/render/Shading.h"
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
        const LodCut cut(tree, camera, settings.lodPixels, settings.level);
        return detail::renderPerPixel(name(), tree, camera, settings, frame,
                              [&](const detail::PixelRays& rays, int x, int y, const dvec3& d, TraversalCounters& c, bool& meets) {
                                  QuantizedRay q = rays.quantized(x, y, d);
                                  ReferenceRay r = quantized_ ? referenceRayFromQuantized(q)
                                                              : referenceRayUnquantized(rays.originOS(x, y), d);
                                  TraversalHit hit = traverseReference(tree, r, c, &cut);
                                  // The unquantized ray can graze a cube face from inside where
                                  // its quantized twin is rounded onto the face (outside): it
                                  // meets the cube when it hits, so that hits <= rays holds.
                                  meets = q.meetsCube || hit.hit();
                                  return hit;
                              });
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
            s.lodPixels = pixels;
            renderer.render(tree, camera, s, frame);
            ++delivered;
            if (!onFrame(frame, pixels)) return delivered;
        }
    }
    s.lodPixels = 0.0;
    s.level = -1;
    renderer.render(tree, camera, s, frame);
    onFrame(frame, 0.0);
    return delivered + 1;
}

std::vector<std::string> rendererNames() {
    return {"full", "linear", "area", "area+colour", "linear-exact", "area-exact", "reference", "reference-unquantized", "direct", "direct-f2b", "samet", "beam"};
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

std::unique_ptr<Renderer> makeRenderer(const std::string& nameIn) {
    using detail::DiscreteRenderer;
    std::string name = nameIn;
    bool colour = false;
    for (const char* suffix : {"+colour", "+color"}) {
        const std::string sfx(suffix);
        if (name.size() > sfx.size() && name.compare(name.size() - sfx.size(), sfx.size(), sfx) == 0) {
            colour = true;
            name.erase(name.size() - sfx.size());
        }
    }
    if (name == "full") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Full, false, colour);
    if (name == "linear") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Linear, false, colour);
    if (name == "area") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Area, false, colour);
    if (name == "linear-exact") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Linear, true, colour);
    if (name == "area-exact") return std::make_unique<DiscreteRenderer>(DiscreteRenderer::Pattern::Area, true, colour);
    if (!colour && name == "reference") return std::make_unique<ReferenceRenderer>(true);
    if (!colour && name == "reference-unquantized") return std::make_unique<ReferenceRenderer>(false);
    if (!colour && name == "direct") return std::make_unique<detail::DirectRenderer>(false);
    if (!colour && name == "direct-f2b") return std::make_unique<detail::DirectRenderer>(true);
    if (!colour)
        if (auto r = detail::makeSphereRenderer(name)) return r;
    std::string list;
    for (const auto& n : rendererNames()) list += (list.empty() ? "" : ", ") + n;
    throw UsageError("unknown renderer '" + nameIn + "' (choose one of: " + list +
                     "; a discrete renderer takes the suffix +colour for colour coherence)");
}

}  // namespace octrace
