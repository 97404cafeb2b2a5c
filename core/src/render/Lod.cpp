#include "octrace/render/Lod.h"

#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>

namespace octrace {

LodCut::LodCut(const Octree& tree, const Camera& camera, double pixels, int level) {
    const bool byPixels = pixels > 0.0, byLevel = level >= 0 && level < tree.depth;
    coarsest_ = tree.depth;
    if (!byPixels && !byLevel) return;
    if (!tree.hasSummaries()) throw UsageError("multi-resolution rendering needs the octree's node summaries (Octree::computeSummaries)");
    active_ = true;
    depth_ = tree.depth;
    maxLevel_ = byLevel ? level : tree.depth;
    coarsest_ = maxLevel_;
    for (int l = 0; l <= Octree::kMaxDepth; ++l) sides_[std::size_t(l)] = std::ldexp(1.0, Octree::kIntBits - l);
    if (!byPixels) return;
    const double toOctree = std::ldexp(1.0, Octree::kIntBits) / tree.cubeSide;
    if (camera.orthographic()) {
        // The projected size depends on the level only: the first level whose edge is below
        // `pixels` pixels.
        const double pixel = camera.orthoHeight / double(camera.height) * toOctree;
        for (int l = 0; l < tree.depth; ++l)
            if (sides_[std::size_t(l)] < pixels * pixel) {
                maxLevel_ = std::min(maxLevel_, l);
                break;
            }
        coarsest_ = maxLevel_;
        return;
    }
    perspective_ = true;
    eye_ = tree.toOctreeSpace(camera.position);
    const double pixelAtUnit = 2.0 * std::tan(glm::radians(camera.fovYDegrees) * 0.5) / double(camera.height);
    k2_ = (pixels * pixelAtUnit) * (pixels * pixelAtUnit);
    // No node centre is farther from the eye than the farthest cube corner: a level whose edge
    // is not below the cut's size at that distance never stops (the test in stops(), with a
    // margin for rounding).
    double far2 = 0.0;
    for (int k = 0; k < 8; ++k) {
        const dvec3 d = dvec3((k >> 2) & 1, (k >> 1) & 1, k & 1) * sides_[0] - eye_;
        far2 = std::max(far2, glm::dot(d, d));
    }
    for (int l = 1; l < maxLevel_; ++l)
        if (sides_[std::size_t(l)] * sides_[std::size_t(l)] < k2_ * far2 * 1.001) {
            coarsest_ = l;
            break;
        }
}

}  // namespace octrace
