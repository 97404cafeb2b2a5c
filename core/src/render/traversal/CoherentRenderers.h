#pragma once
// Private to core: the discrete-traversal renderers (see CoherentRenderers.cpp).
#include "octrace/render/Renderer.h"

namespace octrace::detail {

class DiscreteRenderer final : public Renderer {
public:
    enum class Pattern { Full, Linear, Area };
    DiscreteRenderer(Pattern pattern, bool exact) : pattern_(pattern), exact_(exact) {}
    std::string name() const override;
    RendererTraits traits() const override {
        RendererTraits t;
        t.levelOfDetail = pattern_ == Pattern::Full;
        t.colourCoherence = true;
        t.trajectoryCoherence = pattern_ != Pattern::Full;
        t.missCoherence = pattern_ != Pattern::Full && !exact_;  // never the exact variants
        t.paper = true;
        return t;
    }
    RenderStats render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                       Frame& frame) const override;

private:
    Pattern pattern_;
    bool exact_;
};

}  // namespace octrace::detail
