#pragma once
/// @file DiscreteTraversal.h
/// Discrete integer ray casting in the octree (paper A, section 4), exact by construction.
///
/// The scene cube is octree integer space [0, 2^N)^3, N = Octree::kIntBits. A ray is reduced
/// to its main axis (largest direction component) and its two points on the cube's lower and
/// upper planes perpendicular to that axis, in fixed point with kFracBits fractional bits:
/// this is the *quantized ray* that every exact renderer and the reference trace.
///
/// Semantics (documented rule for ties): each axis whose direction component is negative is
/// mirrored (x -> 2^N - x), so that all components are >= 0; then cells are half-open
/// [lo, hi) on every axis and the ray visits exactly the cells that contain a point of the
/// quantized line with main coordinate >= the eye's. A point on a shared face, edge or corner
/// therefore belongs to the cell the ray moves into. The hit is the first boundary voxel in
/// visiting order, which is strict (no two cells are entered at the same point).
///
/// Inside the traversal everything is integer: per visited node 2 shifts+adds for the lower/
/// upper-point midpoints, 6 adds for the line-line (u,v) terms, 18 comparisons, 4 table
/// look-ups and ANDs (see docs/dev/discrete-traversal.md). Intermediates fit in 64 bits.
#include "octrace/octree/Octree.h"
#include "octrace/render/Frame.h"
#include "octrace/util/Math.h"

#include <cstdint>
#include <functional>

namespace octrace {

struct QuantizedRay {
    static constexpr int kFracBits = 12;

    bool meetsCube = false;         ///< the ray crosses the cube in front of the eye
    int main = 0, u = 1, v = 2;     ///< original axis indices (u < v)
    unsigned sign = 0;              ///< child-index bits of the axes with negative direction
    // Mirrored coordinates, fixed point (kFracBits): u and v on the lower main plane and their
    // change up to the upper plane (both >= 0 after mirroring).
    std::int64_t U0 = 0, dU = 0, V0 = 0, dV = 0;
    std::int64_t eyeM = 0;          ///< mirrored main coordinate of the eye (fixed point), >= 0
    std::int64_t uEyeFloor = 0, vEyeFloor = 0;  ///< floor of u, v of the line at the eye's plane

    /// Point of the quantized line on the lower (t = 0) and upper (t = 1) mirrored main plane,
    /// back in original octree space (exact in double).
    dvec3 lowerPoint() const;
    dvec3 upperPoint() const;
    /// Line parameter of the eye (main coordinate / 2^N), exact as a fraction eyeM / 2^(N+Q).
    double eyeParameter() const;
};

/// Quantizes a ray given in octree integer space (origin, any non-zero direction).
QuantizedRay quantizeRay(const dvec3& originOS, const dvec3& directionOS);
/// quantizeRay(originOS, directionsOS[i]) into out[i] for i < n, bit for bit, eight at a time
/// where the processor has AVX-512.
void quantizeRays(const dvec3& originOS, const dvec3* directionsOS, int n, QuantizedRay* out);

struct TraversalHit {
    std::uint32_t voxel = kNoHit;  ///< index into Octree::voxels() (for a node hit: its summary's firstVoxel)
    ivec3 cell{0};                 ///< voxel coordinates in cell space (for a node hit: at its level;
                                   ///< for a coarse leaf: its lowest voxel cell)
    int leafShift = 0;             ///< voxel hits: the leaf's side is 2^leafShift voxels (> 0: a coarse leaf, Octree.h)
    std::uint32_t node = kNoHit;   ///< multi-resolution: the inner node drawn instead of a voxel
    int level = 0;                 ///< the node's level (node hits only)
    /// Smooth surfaces (SmoothSurface.h): the hit lies on the field's interpolant inside the
    /// voxel, at `distance` along the unit world ray, with the unit normal `normal` (towards
    /// lower values), at height `zCells` (cell space along z: what colouring by height reads).
    /// False: the voxel's box is the hit.
    bool smooth = false;
    double distance = 0.0;
    vec3 normal{0.0f};
    float zCells = 0.0f;
    bool hit() const { return voxel != kNoHit; }
    bool nodeHit() const { return node != kNoHit; }
};

/// Decides whether a voxel the traversal reaches is its hit (true) or is passed (false), and may
/// fill in the hit's smooth part; called once per reached voxel, in visiting order, never for a
/// node drawn whole by a cut. The smooth surfaces' test (SmoothSurface.h).
using VoxelFilter = std::function<bool(TraversalHit&)>;

struct TraversalCounters {
    std::uint64_t nodes = 0;           ///< inner nodes whose state byte was computed
    std::uint64_t statesDeferred = 0;  ///< guided mode: path nodes whose state was never needed
};

class LodCut;

/// The discrete integer traversal. Thread-safe. With a cut (Lod.h), it stops at the first
/// crossed non-empty node the cut says to stop at and returns it as a node hit.
/// With a filter, a voxel it refuses is passed and the traversal goes on behind it.
TraversalHit traverseDiscrete(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters,
                              const LodCut* cut = nullptr, const VoxelFilter* filter = nullptr);

/// Same traversal, reporting every state byte it computes (sign pattern, byte in original
/// child numbering, before masking with the node's children). For tests.
TraversalHit traverseDiscreteObserved(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters,
                                      const std::function<void(unsigned sign, unsigned stateByte)>& observe);

/// Whether the quantized ray visits the cell (original coordinates at `level`, 0 .. depth of
/// the finest lattice Octree::kMaxDepth): the state byte's exact interval tests for one box,
/// under the same semantics (half-open mirrored cells, in front of the eye). Thread-safe.
bool rayCrossesCell(const QuantizedRay& ray, const ivec3& cell, int level);

/// The discrete traversal restricted to one inner node (original cell coordinates `cell` at
/// `level`, node index `node` of Octree::nodes(), level < the tree's depth): the first boundary
/// voxel of the node's subtree in the ray's visiting order, exactly as traverseDiscrete orders
/// them; no hit when the ray does not cross the node or finds nothing in it. The tile renderer
/// starts its rays here (docs/dev/tile-renderer.md). Thread-safe.
TraversalHit traverseFromNode(const Octree& tree, const QuantizedRay& ray, std::uint32_t node, int level,
                              const ivec3& cell, TraversalCounters& counters);

/// An inner node to start a traversal from: its index in Octree::nodes(), level and cell.
struct StartNode {
    std::uint32_t node = 0;
    int level = 0;
    ivec3 cell{0};
};
/// traverseFromNode on each of `count` nodes in turn until one gives a hit (one set-up for
/// all). The caller orders the nodes so that this is the ray's first hit among them. With a
/// filter, as traverseDiscrete: a refused voxel is passed and the search goes on behind it,
/// through the rest of its node and the nodes after it. With a cut, as traverseDiscrete: a
/// crossed non-empty node the cut stops at is the hit (the start nodes themselves must lie
/// above LodCut::coarsestLevel()).
TraversalHit traverseFromNodes(const Octree& tree, const QuantizedRay& ray, const StartNode* nodes, std::size_t count,
                               TraversalCounters& counters, const VoxelFilter* filter = nullptr, const LodCut* cut = nullptr);

/// Samet's neighbour finding on the voxel octree (renderer samet): the ray goes leaf to leaf,
/// from the leaf holding its first point; at each leaf its exit point, the neighbour of equal
/// size across the exit face, edge or corner (climb the root-to-leaf path to the common
/// ancestor, descend the mirrored path), then down to the leaf holding the exit point. Exact
/// rational arithmetic on the quantized line: the same hit as traverseDiscrete.
/// counters.nodes counts the inner nodes stepped through. Thread-safe.
TraversalHit traverseSamet(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters);

/// An inner node where a coherent ray starts: the smallest node holding the hit voxels of two
/// neighbouring rays (the *branch node* of their common path), with its path from the root.
struct BranchNode {
    int level = -1;                                  ///< -1: none
    ivec3 cell{0};                                   ///< its coordinates at its level
    std::uint32_t path[Octree::kMaxDepth + 1] = {};  ///< node indices: path[0] = root .. path[level]
    std::uint8_t childIndex[Octree::kMaxDepth] = {}; ///< child of path[i] that leads to path[i+1]
    bool valid() const { return level >= 0; }
};

/// Branch node of two boundary voxels (their smallest common ancestor, at most at level
/// depth-1), or its ancestor `up` levels above it (at the root at most). Invalid when a cell
/// is not a boundary voxel of the tree.
BranchNode branchNode(const Octree& tree, const ivec3& cellA, const ivec3& cellB, int up = 0);

/// Paper A's trajectory coherence, approximate: traverses only the branch node's subtree; when
/// the ray does not cross the node or finds nothing in it, retraces from the root
/// (fellBack = true). The hit can differ from the full traversal's when something in front of
/// the branch node lies on this ray but not on the supporting rays.
TraversalHit traverseFromBranch(const Octree& tree, const QuantizedRay& ray, const BranchNode& branch,
                                TraversalCounters& counters, bool& fellBack);

/// The children (bit c = child c) of a node that a ray of sign pattern `sign` can cross before
/// its child `child`: those whose mirrored bits are a proper subset of its (the children one ray
/// crosses are visited in the order of their mirrored bits under inclusion).
std::uint8_t predecessorChildren(unsigned sign, unsigned child);

/// Trajectory coherence, exact: the full traversal, guided down the branch node's path. At a
/// path node whose non-empty children cannot precede the path child for this ray's sign
/// pattern (a property of the tree, not of the ray), nothing can lie in front on that level,
/// so the node's state byte is not computed unless the search comes back to it. Always
/// returns the full traversal's hit. certified = the hit was found below the branch node with
/// no state byte computed above it (the ray skipped the root).
TraversalHit traverseGuided(const Octree& tree, const QuantizedRay& ray, const BranchNode& branch,
                            TraversalCounters& counters, bool& certified);

}  // namespace octrace
