#include "octrace/octree/Octree.h"

#include <climits>

namespace octrace {

void Octree::occupiedCells(ivec3& lo, ivec3& hi) const {
    lo = ivec3(INT_MAX);
    hi = ivec3(INT_MIN);
    forEachLeaf([&](const ivec3& c, int shift, std::uint32_t) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c + ((1 << shift) - 1));
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
