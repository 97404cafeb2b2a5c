#include "octrace/octree/Octree.h"

#include <climits>

namespace octrace {

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
