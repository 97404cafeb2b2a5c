#pragma once
// Private to core: the primary ray of each pixel, in world space (for depth) and quantized
// in octree space (for the traversals). Every renderer takes its rays from here, so that the
// exact renderers and the reference trace bitwise the same quantized rays.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/DiscreteTraversal.h"

namespace octrace::detail {

class PixelRays {
public:
    PixelRays(const Octree& tree, const Camera& camera) : tree_(tree), gen_(camera) {}
    /// Unnormalised world direction of pixel (x, y) (quantization only needs its ratios).
    dvec3 direction(int x, int y) const { return gen_.direction(x, y); }
    /// Ray origin of pixel (x, y) in octree space.
    dvec3 originOS(int x, int y) const { return tree_.toOctreeSpace(gen_.origin(x, y)); }
    QuantizedRay quantized(int x, int y, const dvec3& direction) const { return quantizeRay(originOS(x, y), direction); }
    /// The world ray (unit direction), for the distance of a hit.
    Ray world(int x, int y, const dvec3& direction) const { return {gen_.origin(x, y), glm::normalize(direction)}; }

private:
    const Octree& tree_;
    RayGenerator gen_;
};

}  // namespace octrace::detail
