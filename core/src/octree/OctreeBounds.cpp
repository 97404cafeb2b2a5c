#include "octrace/octree/Octree.h"

#include <climits>
#include <mutex>

namespace octrace {

/// What occupiedCells found last, and for which nodes (their buffer and count), depth and form.
struct Octree::OccupiedCache {
    std::mutex mutex;
    bool valid = false;
    const OctreeNode* nodes = nullptr;
    std::size_t count = 0;
    int depth = 0;
    OctreeForm form = OctreeForm::Shell;
    ivec3 lo{0}, hi{0};
};

Octree::Octree() : occupied_(std::make_unique<OccupiedCache>()) {}
Octree::Octree(Octree&&) noexcept = default;
Octree& Octree::operator=(Octree&&) noexcept = default;
Octree::~Octree() = default;

void Octree::forgetOccupiedCells() {
    if (!occupied_) return;
    const std::lock_guard<std::mutex> lock(occupied_->mutex);
    occupied_->valid = false;
}

void Octree::occupiedCells(ivec3& lo, ivec3& hi) const {
    std::unique_lock<std::mutex> lock;
    if (occupied_) {
        lock = std::unique_lock<std::mutex>(occupied_->mutex);
        const OccupiedCache& c = *occupied_;
        if (c.valid && c.nodes == nodes_.data() && c.count == nodes_.size() && c.depth == depth && c.form == form) {
            lo = c.lo;
            hi = c.hi;
            return;
        }
    }
    findOccupiedCells(lo, hi);
    if (!occupied_) return;
    OccupiedCache& c = *occupied_;
    c.valid = true;
    c.nodes = nodes_.data();
    c.count = nodes_.size();
    c.depth = depth;
    c.form = form;
    c.lo = lo;
    c.hi = hi;
}

void Octree::findOccupiedCells(ivec3& lo, ivec3& hi) const {
    lo = ivec3(INT_MAX);
    hi = ivec3(INT_MIN);
    if (depth < 1) return;
    // The leaves of forEachLeaf, without entering a node whose cells all lie inside the box
    // found so far (none of its leaves can widen it). Renderers ask for this every frame.
    descend([&](int l, const ivec3& cell, std::uint32_t, bool term) {
        const int shift = depth - l;
        const ivec3 c0 = cell << shift, c1 = c0 + ((1 << shift) - 1);
        if (l == depth || (term && form == OctreeForm::Shell)) {
            lo = glm::min(lo, c0);
            hi = glm::max(hi, c1);
            return false;
        }
        if (term) return false;  // volume form: interior terms above the voxels are not leaves
        return !(glm::all(glm::greaterThanEqual(c0, lo)) && glm::all(glm::lessThanEqual(c1, hi)));
    });
}

Box3 Octree::occupiedBounds() const {
    ivec3 lo, hi;
    occupiedCells(lo, hi);
    if (lo.x > hi.x) return Box3{cubeOrigin, cubeOrigin + dvec3(cubeSide)};
    Box3 b;
    b.lo = cubeOrigin + dvec3(lo) * voxelSize();
    b.hi = cubeOrigin + dvec3(hi + 1) * voxelSize();
    return b;
}

}  // namespace octrace
