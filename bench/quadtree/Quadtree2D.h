#pragma once
/// @file Quadtree2D.h
/// Paper B's own experiment (its Figure 5) in the plane: circles in a quadtree built as the
/// object octree is (a node splits while it holds more than `leafObjects` circles), a fan of
/// rays from an eye in the plane, and three tracers that must agree ray for ray: brute force,
/// Samet's leaf-to-leaf neighbour finding, and beam tracing (a beam is the eye and an interval
/// of the fan; it is split at each leaf's exit faces and at the sizes of the neighbours behind
/// them; in empty leaves only the beams move, in occupied ones the beam's rays are selected by
/// binary search in the sorted fan and intersected one by one). docs/dev/spheres.md, "Figure 5
/// in 2D", has the design and the 2D SphereFlake's definition.
#include "octrace/util/Math.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace octrace::quad {

struct Circle {
    dvec2 centre{0.0};
    double radius = 0.0;
};

struct Scene2D {
    std::string name;
    std::vector<Circle> circles;
};

/// The 2D SphereFlake: a circle of radius 1/2 at the origin; each circle of the flake carries,
/// tangent to it outside, circles of a third of its radius: six around the first one (every
/// 60 degrees), five on every other (every 60 degrees but the direction back to its parent),
/// down to `level` generations (0 .. 7): 1 + 6 (5^level - 1) / 4 circles (level 4: 937).
Scene2D makeFlake2D(int level);
/// `count` circles (1 .. 10^6) with centres uniform in the unit square and radii uniform in
/// [0.2, 1] x `radius`, from a 64-bit Mersenne Twister with `seed` (the same on every machine).
Scene2D makeRandom2D(std::size_t count, std::uint64_t seed, double radius = 0.01);

struct QuadNode {
    std::uint32_t parent = 0;       ///< the root is its own parent
    std::uint32_t firstChild = 0;   ///< 0: a leaf; else children at firstChild + q (q = 2x + y)
    std::uint32_t firstObject = 0;  ///< leaves: range in Quadtree::objects
    std::uint32_t objectCount = 0;
    std::uint32_t cell[2] = {0, 0}; ///< minimum corner on the grid of level kMaxDepth
    std::uint8_t level = 0;
    std::uint8_t quadrant = 0;      ///< child index in the parent
    bool leaf() const { return firstChild == 0; }
};

class Quadtree {
public:
    static constexpr int kMaxDepth = 24;
    Scene2D scene;
    dvec2 origin{0.0};  ///< the square's minimum corner
    double side = 1.0;
    int depth = 0;
    std::vector<QuadNode> nodes;          ///< nodes[0] = root
    std::vector<std::uint32_t> objects;   ///< leaves' circle lists

    /// Splits while a node holds more than leafObjects circles (whose bounding squares meet
    /// it) and is above maxDepth. UsageError for leafObjects < 1, maxDepth outside 1 .. 24 or
    /// an empty scene.
    static Quadtree build(Scene2D scene, int leafObjects = 8, int maxDepth = 16);

    /// The node's square from its integer cell, so that neighbours share coordinates bit for bit.
    void box(std::uint32_t n, dvec2& lo, dvec2& hi) const;
    std::size_t leaves() const;
    std::size_t occupiedLeaves() const;
    /// From node n down to the leaf holding p; on an edge or a corner, the child `dir` points into.
    std::uint32_t descendToLeaf(std::uint32_t n, const dvec2& p, const dvec2& dir) const;
    /// Samet's edge neighbour of n across its side on `axis` (positive: the high side), of equal
    /// or larger size: climb to the first common ancestor, descend the mirrored path while the
    /// nodes exist. kNone on the square's boundary.
    std::uint32_t neighbour(std::uint32_t n, int axis, bool positive) const;
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
};

/// A fan of n rays from `eye`: ray i has the direction forward + u_i right (not normalised),
/// u_i = u0 + (i + 1/2)(u1 - u0)/n, so the rays are sorted by u, as pixels on a screen line.
/// u of a point p is dot(p - eye, right) / dot(p - eye, forward).
struct Fan {
    dvec2 eye{0.0};
    dvec2 forward{1.0, 0.0};  ///< unit
    dvec2 right{0.0, 1.0};    ///< unit, perpendicular to forward
    double u0 = -1.0, u1 = 1.0;
    std::size_t n = 0;
    double u(std::size_t i) const { return u0 + (double(i) + 0.5) * (u1 - u0) / double(n); }
    dvec2 direction(std::size_t i) const { return forward + u(i) * right; }
    double uOf(const dvec2& p) const { return glm::dot(p - eye, right) / glm::dot(p - eye, forward); }
};

/// A fan of n rays from `eye` that just covers the tree's square (eye outside it, at a
/// distance of at least half the side from it: UsageError otherwise).
Fan fanOver(const Quadtree& tree, const dvec2& eye, std::size_t n);

struct Hit2D {
    double t = std::numeric_limits<double>::infinity();
    std::uint32_t circle = 0xFFFFFFFFu;
    bool hit() const { return circle != 0xFFFFFFFFu; }
    bool operator==(const Hit2D&) const = default;
};

struct Trace2DCounters {
    std::uint64_t nodes = 0;          ///< leaves visited by a ray (Samet) or a beam
    std::uint64_t neighbourSteps = 0; ///< neighbour findings
    std::uint64_t intersections = 0;  ///< ray-circle tests
    std::uint64_t beams = 0;          ///< beams processed (beam tracing)
    std::uint64_t raySelections = 0;  ///< rays picked out of beams in occupied leaves
};

/// Nearest intersection at t > 0 of origin + t dir with the circle; +inf when none.
double intersectCircle(const Circle& c, const dvec2& origin, const dvec2& dir);

/// Every circle for every ray (the reference).
std::vector<Hit2D> traceBruteForce(const Scene2D& scene, const Fan& fan);
/// One ray at a time, leaf to leaf by Samet's neighbour finding.
std::vector<Hit2D> traceSamet(const Quadtree& tree, const Fan& fan, Trace2DCounters& c);
/// Beam tracing of the whole fan.
std::vector<Hit2D> traceBeams(const Quadtree& tree, const Fan& fan, Trace2DCounters& c);

}  // namespace octrace::quad
