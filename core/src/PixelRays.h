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
    PixelRays(const Octree& tree, const Camera& camera) : gen_(camera), originOS_(tree.toOctreeSpace(camera.position)) {}
    /// Unnormalised world direction of pixel (x, y) (quantization only needs its ratios).
    dvec3 direction(int x, int y) const { return gen_.direction(x, y); }
    QuantizedRay quantized(const dvec3& direction) const { return quantizeRay(originOS_, direction); }
    const dvec3& originOS() const { return originOS_; }
    /// The world ray (unit direction), for the distance of a hit.
    Ray world(const dvec3& direction) const { return {gen_.origin(), glm::normalize(direction)}; }

private:
    RayGenerator gen_;
    dvec3 originOS_;
};

}  // namespace octrace::detail
