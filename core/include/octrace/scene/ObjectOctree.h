#pragma once
/// @file ObjectOctree.h
/// Paper B's object octree over a SphereSet: a node is split into its 8 octants while it holds
/// more than `leafObjects` spheres (and is above `maxDepth`, and the split would not copy its
/// list into the children more than 4 times over: spheres that overlap too much stay together); leaves keep the list of the
/// spheres whose bounding box meets them; every node keeps its parent, for Samet's neighbour
/// finding. Rays meet the spheres analytically.
///
/// Node boxes are computed from integer coordinates on the grid of the finest possible level
/// (cubeOrigin + cell * step), so two nodes that share a face share its coordinate bit for
/// bit, and a ray's parameter on that face is the same number in both.
#include "octrace/scene/Spheres.h"
#include "octrace/util/Math.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace octrace {

struct ObjectNode {
    std::uint32_t parent = 0;      ///< the root is its own parent
    std::uint32_t firstChild = 0;  ///< 0: a leaf; else the 8 children at firstChild + c (c = 4x + 2y + z)
    std::uint32_t firstObject = 0; ///< leaves: range in ObjectOctree::objects
    std::uint32_t objectCount = 0;
    std::uint32_t cell[3] = {0, 0, 0};  ///< minimum corner on the grid of level kMaxDepth
    std::uint8_t level = 0;
    std::uint8_t octant = 0;       ///< child index in the parent
    bool leaf() const { return firstChild == 0; }
};

struct ObjectOctreeOptions {
    /// Split a node while it holds more spheres than this. Default 8: paper B splits "while a
    /// node holds more objects than a threshold" without giving it; 8 keeps the analytic tests
    /// per occupied leaf few while the tree stays small (docs/dev/spheres.md).
    int leafObjects = 8;
    int maxDepth = 10;  ///< 1 .. kMaxDepth; overlapping spheres stop the splitting there
    std::uint64_t memoryBudget = 0;  ///< bytes, 0 = no limit (LimitError when exceeded)
};

/// intersectSphere from the terms that depend on the ray's origin only: oc = centre - origin
/// and c = dot(oc, oc) - radius^2. Rays that share an origin (a perspective eye) compute them
/// once per sphere and get the same number as intersectSphere, which is this function.
inline double intersectSphereFrom(const dvec3& oc, double c, const dvec3& dir, double tMin) {
    // |o + t d - c|^2 = r^2 with |d| = 1: t = b -+ sqrt(b^2 - (|o-c|^2 - r^2)), b = d.(c-o).
    const double b = glm::dot(dir, oc);
    const double disc = b * b - c;
    if (disc < 0.0) return std::numeric_limits<double>::infinity();
    const double q = std::sqrt(disc);
    const double t0 = b - q;
    if (t0 >= tMin) return t0;
    const double t1 = b + q;
    return t1 >= tMin ? t1 : std::numeric_limits<double>::infinity();
}

/// Nearest intersection of a ray with a sphere at a parameter t >= tMin (the entry point, or
/// the exit point from inside); +inf when none. The one function every tracer uses, so that
/// they all compute the same number for the same ray and sphere.
inline double intersectSphere(const Sphere& s, const dvec3& origin, const dvec3& dir, double tMin) {
    const dvec3 oc = s.centre - origin;
    return intersectSphereFrom(oc, glm::dot(oc, oc) - s.radius * s.radius, dir, tMin);
}

class ObjectOctree {
public:
    static constexpr int kMaxDepth = 20;
    ObjectOctree() = default;
    ObjectOctree(ObjectOctree&&) noexcept = default;
    ObjectOctree& operator=(ObjectOctree&&) noexcept = default;
    ObjectOctree(const ObjectOctree&) = delete;
    ObjectOctree& operator=(const ObjectOctree&) = delete;

    SphereSet scene;
    dvec3 cubeOrigin{0.0};
    double cubeSide = 1.0;
    int depth = 0;                       ///< deepest level reached
    int leafObjects = 8;
    std::vector<ObjectNode> nodes;       ///< nodes[0] = root
    std::vector<std::uint32_t> objects;  ///< leaves' sphere lists (ascending indices)

    /// Throws UsageError for leafObjects < 1 or a maxDepth out of range, LimitError past the
    /// budget, and as SphereSet::validate.
    static ObjectOctree build(SphereSet scene, const ObjectOctreeOptions& options = {});

    Box3 nodeBox(std::uint32_t n) const {
        const ObjectNode& nd = nodes[n];
        const double step = cubeSide / double(1u << kMaxDepth);
        const std::uint32_t size = 1u << (kMaxDepth - nd.level);
        Box3 b;
        for (int a = 0; a < 3; ++a) {
            b.lo[a] = cubeOrigin[a] + double(nd.cell[a]) * step;
            b.hi[a] = cubeOrigin[a] + double(nd.cell[a] + size) * step;
        }
        return b;
    }
    Box3 cube() const { return {cubeOrigin, cubeOrigin + dvec3(cubeSide)}; }
    std::size_t leaves() const;
    std::size_t occupiedLeaves() const;
    std::size_t bytes() const { return nodes.capacity() * sizeof(ObjectNode) + objects.capacity() * 4 + scene.spheres.capacity() * sizeof(Sphere); }

    /// Leaf containing point p (clamped into the cube); on a face between two leaves, the one
    /// on the side `dir` points to.
    std::uint32_t locateLeaf(const dvec3& p, const dvec3& dir) const { return descendToLeaf(0, p, dir); }
    /// From node n down to the leaf containing p (ties broken towards dir), as locateLeaf.
    std::uint32_t descendToLeaf(std::uint32_t n, const dvec3& p, const dvec3& dir) const;
    /// Samet's face neighbour of node n across its face on `axis` (0..2) at the high side
    /// (`positive`) or low side: climbs to the first common ancestor, then descends the
    /// mirrored path while the nodes exist. The result is of equal or larger size than n
    /// (a leaf or not); 0xFFFFFFFF when that face is on the cube's boundary. `climbed`
    /// (optional) counts the nodes climbed and descended.
    std::uint32_t faceNeighbour(std::uint32_t n, int axis, bool positive, std::uint64_t* steps = nullptr) const;

    /// Structural checks (children, parents, cells, object ranges, lists in ascending order). Throws Error.
    void validate() const;
};

/// What a tracer found along one ray.
struct SphereHit {
    double t = std::numeric_limits<double>::infinity();
    std::uint32_t sphere = 0xFFFFFFFFu;
    bool hit() const { return sphere != 0xFFFFFFFFu; }
};

struct ObjectTraceCounters {
    std::uint64_t nodes = 0;        ///< nodes stepped through (leaves visited, neighbour steps)
    std::uint64_t intersections = 0;///< ray-sphere tests
};

/// The floating-point reference: a recursive parametric traversal (slab test on all 8 children,
/// visited by entry parameter), written independently of the neighbour finding and the beams.
/// In each leaf it takes the nearest sphere hit at t >= tMin that is not beyond the leaf's exit;
/// the first leaf that has one ends the ray. Thread-safe.
SphereHit traceReference(const ObjectOctree& tree, const dvec3& origin, const dvec3& dir, double tMin, ObjectTraceCounters& c);
/// Samet's method: from the leaf where the ray enters, leaf to leaf by faceNeighbour and the
/// descent to the leaf that holds the exit point, with the same rule in each leaf. Thread-safe.
SphereHit traceSamet(const ObjectOctree& tree, const dvec3& origin, const dvec3& dir, double tMin, ObjectTraceCounters& c);
/// The rule every tracer applies in a leaf it crosses: the nearest of the leaf's spheres hit at
/// t >= tMin, provided that it is not beyond tExit (the ray's exit from the leaf); else no hit.
SphereHit nearestInLeaf(const ObjectOctree& tree, const ObjectNode& leaf, const dvec3& origin, const dvec3& dir, double tMin,
                        double tExit, ObjectTraceCounters& c);
/// Brute force over every sphere (tests only: O(spheres) per ray).
SphereHit traceBruteForce(const SphereSet& scene, const dvec3& origin, const dvec3& dir, double tMin);

/// The parameter interval [t0, t1] in which the ray is inside box b (t0 > t1: it misses).
/// Division-free zero directions are handled (an axis-parallel ray inside the slab is
/// unbounded there).
void slabInterval(const Box3& b, const dvec3& origin, const dvec3& invDir, const dvec3& dir, double& t0, double& t1);

}  // namespace octrace
