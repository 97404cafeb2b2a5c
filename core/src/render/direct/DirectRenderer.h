#pragma once
// Private to core: the direct (object-order) renderers, see DirectRenderer.cpp.
#include "octrace/render/Renderer.h"

namespace octrace::detail {

class DirectRenderer final : public Renderer {
public:
    explicit DirectRenderer(bool frontToBack) : frontToBack_(frontToBack) {}
    std::string name() const override;
    RendererTraits traits() const override {
        RendererTraits t;
        t.tracesRays = false;
        t.paper = true;
        return t;
    }
    RenderStats render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                       Frame& frame) const override;

private:
    bool frontToBack_;
};

}  // namespace octrace::detail
