#include "octrace/model/Verify.h"

#include "octrace/render/ImageCompare.h"

#include <algorithm>
#include <cmath>

namespace octrace::model {

Verification verifyFrame(const Octree& tree, const Camera& camera, const RenderSettings& settings, const Frame& frame,
                         const Renderer& renderer, int repeat) {
    Verification v;
    const auto reference = makeRenderer("reference");
    Frame rf;
    RenderStats rst = renderAntialiased(*reference, tree, camera, settings, rf);
    for (int i = 1; i < repeat; ++i) rst.renderMs = std::min(rst.renderMs, renderAntialiased(*reference, tree, camera, settings, rf).renderMs);
    for (std::size_t i = 0; i < frame.hitId.size(); ++i)
        v.mismatchedPixels += !(frame.flags[i] & Frame::kColourFilled) && frame.hitId[i] != rf.hitId[i];
    const ImageDifference d = compareImages(frame, rf);
    v.psnrDb = d.psnrDb;
    v.maxChannelError = d.maxChannelError;
    v.referenceMs = rst.renderMs;
    v.referenceUsPerRay = rst.rays ? rst.renderMs * 1000.0 / double(rst.rays) : 0.0;

    Frame uf;
    renderAntialiased(*makeRenderer("reference-unquantized"), tree, camera, settings, uf);
    for (std::size_t i = 0; i < rf.hitId.size(); ++i) v.unquantizedMismatchedPixels += rf.hitId[i] != uf.hitId[i];

    std::uint64_t either = 0, both = 0;
    double depthErr = 0.0;
    for (std::size_t i = 0; i < rf.hitId.size(); ++i) {
        const bool h = frame.hitId[i] != kNoHit, r = rf.hitId[i] != kNoHit;
        either += h || r;
        both += h && r;
        if (h && r) depthErr = std::max(depthErr, double(std::abs(frame.depth[i] - rf.depth[i])));
    }
    v.hitAgreement = either ? double(both) / double(either) : 1.0;
    v.depthMaxErrorDiagonals = depthErr / (tree.voxelSize() * std::sqrt(3.0));

    if (settings.detail.active(tree.depth)) {
        RenderSettings exactSettings = settings;
        exactSettings.detail.lodPixels = 0.0;
        exactSettings.detail.level = -1;
        Frame exact;
        renderAntialiased(renderer, tree, camera, exactSettings, exact);
        v.levelOfDetail = compareImages(frame, exact);
    }
    return v;
}

}  // namespace octrace::model
