#include "lighting/ShadowTracer.h"

#include "octrace/render/DiscreteTraversal.h"

#include <algorithm>
#include <cmath>

namespace octrace::detail {
namespace {

double entry(const dvec3& o, const dvec3& d, const Box3& b) {
    double t = 0.0;
    for (int a = 0; a < 3; ++a)
        if (d[a] != 0.0) t = std::max(t, std::min((b.lo[a] - o[a]) / d[a], (b.hi[a] - o[a]) / d[a]));
    return t;
}

double exit(const dvec3& o, const dvec3& d, const Box3& b) {
    double t = INFINITY;
    for (int a = 0; a < 3; ++a)
        if (d[a] != 0.0) t = std::min(t, std::max((b.lo[a] - o[a]) / d[a], (b.hi[a] - o[a]) / d[a]));
    return t;
}

}  // namespace

ShadowTracer::ShadowTracer(const Octree& tree) : t_(tree), toOS_(double(1u << Octree::kIntBits) / tree.cubeSide) {}

double ShadowTracer::firstHit(dvec3 origin, const dvec3& dir, const ivec3& start, int startShift, std::uint64_t& rays) const {
    const double h = t_.voxelSize();
    const ivec3 startHi = start + ivec3((1 << startShift) - 1);
    double travelled = 0.0;
    for (int attempt = 0; attempt < 4; ++attempt) {
        ++rays;
        TraversalCounters counters;
        const QuantizedRay q = quantizeRay(t_.toOctreeSpace(origin), dir * toOS_);
        if (!q.meetsCube) return INFINITY;
        const TraversalHit hit = traverseDiscrete(t_, q, counters);
        if (!hit.hit()) return INFINITY;
        // The hit leaf's box (a coarse leaf's cell is its lowest voxel cell).
        const int side = 1 << hit.leafShift;
        const ivec3 lo = hit.cell, hi = hit.cell + ivec3(side - 1);
        Box3 box;
        box.lo = t_.cubeOrigin + dvec3(lo) * h;
        box.hi = box.lo + dvec3(double(side) * h);
        const double tin = entry(origin, dir, box), tout = exit(origin, dir, box);
        const bool neighbour = glm::all(glm::lessThanEqual(lo, startHi + 1)) && glm::all(glm::lessThanEqual(start, hi + 1));
        if (!neighbour) return travelled + tin;
        // The surface's own neighbour: continue just past it.
        const double step = std::max(tout, 0.0) + 1e-3 * h;
        origin += dir * step;
        travelled += step;
    }
    return INFINITY;
}

bool ShadowTracer::seesDirectionalLight(const ivec3& cell, int shift, const dvec3& n, const dvec3& dir, std::uint64_t& rays) const {
    const double cosine = glm::dot(n, dir);
    if (cosine == 0.0) return true;
    const double h = t_.voxelSize(), side = h * double(1 << shift);
    const dvec3 centre = t_.cubeOrigin + (dvec3(cell) + 0.5 * double(1 << shift)) * h;  // as the bake's voxel centres
    return firstHit(centre + (cosine > 0.0 ? n : -n) * side, dir, cell, shift, rays) == INFINITY;
}

}  // namespace octrace::detail
