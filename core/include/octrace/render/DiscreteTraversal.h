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

struct TraversalHit {
    std::uint32_t voxel = kNoHit;  ///< index into Octree::voxels
    ivec3 cell{0};                 ///< voxel coordinates in cell space
    bool hit() const { return voxel != kNoHit; }
};

struct TraversalCounters {
    std::uint64_t nodes = 0;  ///< inner nodes whose state byte was computed
};

/// The discrete integer traversal. Thread-safe.
TraversalHit traverseDiscrete(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters);

/// Same traversal, reporting every state byte it computes (sign pattern, byte in original
/// child numbering, before masking with the node's children). For tests.
TraversalHit traverseDiscreteObserved(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters,
                                      const std::function<void(unsigned sign, unsigned stateByte)>& observe);

}  // namespace octrace
