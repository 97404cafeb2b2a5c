#pragma once
/// @file Lod.h
/// Multi-resolution rendering: where a traversal stops above the voxels and draws an inner
/// node as a solid box with its subtree's average (Octree::summaries()).
///
/// The cut depends only on a node's level and cell and on the camera, and is evaluated in the
/// same double arithmetic by every renderer, so all renderers draw the same cut tree: `full`
/// and `reference` still agree bit for bit, and the direct renderers agree with them as they
/// do without a cut.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"

#include <array>

namespace octrace {

class LodCut {
public:
    /// No cut: every traversal goes down to the voxels.
    LodCut() = default;
    /// `pixels` > 0: stop at a node whose projected size is below that many pixels (its edge
    /// over its centre's distance from the eye, perspective; its edge over the pixel size,
    /// orthographic). `level` in [0, depth): stop at that level at the latest; < 0: no limit.
    /// Throws UsageError when a cut is asked of a tree without summaries.
    LodCut(const Octree& tree, const Camera& camera, double pixels, int level);

    bool active() const { return active_; }
    /// The coarsest level at which stops() can be true for any node (the tree's depth when the
    /// cut is inactive): every node drawn whole lies on the node grid of that level or finer.
    int coarsestLevel() const { return coarsest_; }
    /// Whether a traversal that reaches the (non-empty, crossed) node at `level` with cell
    /// coordinates `cell` (at that level) stops there. Never at the voxel level.
    bool stops(int level, const ivec3& cell) const {
        if (!active_ || level >= depth_) return false;
        if (level >= maxLevel_) return true;
        if (!perspective_) return false;
        const double side = sides_[std::size_t(level)];
        const dvec3 d = (dvec3(cell) + 0.5) * side - eye_;
        return side * side < k2_ * glm::dot(d, d);
    }

private:
    bool active_ = false, perspective_ = false;
    int depth_ = 0, maxLevel_ = 0, coarsest_ = Octree::kMaxDepth;
    dvec3 eye_{0.0};   // octree integer space
    double k2_ = 0.0;  // (pixels * pixel size at unit distance)^2
    std::array<double, Octree::kMaxDepth + 1> sides_{};
};

}  // namespace octrace
