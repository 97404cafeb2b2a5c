#pragma once
// Private to core: the discrete-traversal renderers (see CoherentRenderers.cpp).
#include "octrace/render/Renderer.h"

namespace octrace::detail {

class DiscreteRenderer final : public Renderer {
public:
    enum class Pattern { Full, Linear, Area };
    DiscreteRenderer(Pattern pattern, bool exact, bool colour) : pattern_(pattern), exact_(exact), colour_(colour) {}
    std::string name() const override;
    bool multiResolution() const override { return pattern_ == Pattern::Full; }
    bool colourCoherence() const override { return true; }
    bool fillsByColour() const override { return colour_; }
    bool trajectoryCoherence() const override { return pattern_ != Pattern::Full; }
    bool missCoherence() const override { return pattern_ != Pattern::Full && !exact_; }
    RenderStats render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                       Frame& frame) const override;

private:
    Pattern pattern_;
    bool exact_, colour_;
};

}  // namespace octrace::detail
