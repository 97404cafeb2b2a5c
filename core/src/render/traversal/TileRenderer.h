#pragma once
// Private to core: the tile renderer (`--renderer tile`), exact: the same hit voxel as `full`
// for every pixel. Why: docs/dev/tile-renderer.md.
#include "octrace/render/Renderer.h"

namespace octrace::detail {

class TileRenderer final : public Renderer {
public:
    /// `widen`: whether the tile pre-pass widens node boxes by the quantization bound (always,
    /// except in the test that shows the widening is needed).
    explicit TileRenderer(bool widen = true) : widen_(widen) {}
    std::string name() const override { return "tile"; }
    RendererTraits traits() const override {
        RendererTraits t;
        t.tiled = true;
        return t;
    }
    RenderStats render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                       Frame& frame) const override;

private:
    bool widen_;
};

}  // namespace octrace::detail
