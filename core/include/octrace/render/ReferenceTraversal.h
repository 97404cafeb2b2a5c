#pragma once
/// @file ReferenceTraversal.h
/// The oracle: a plain floating-point parametric traversal of the octree, written
/// independently of the discrete one (no state bytes, no order table, no fixed point). At
/// each node it runs a slab test on every non-empty child and visits the crossed children
/// sorted by their entry parameter.
///
/// With a QuantizedRay it traces exactly the same line as the discrete traversal, under the
/// same semantics (see DiscreteTraversal.h); the fractions it compares are products of
/// numbers with at most 28 significant bits, exact in long double (64-bit mantissa), so its
/// answer is exact and the discrete traversal must agree with it voxel for voxel.
/// With an unquantized ray it traces the ray itself in double precision; the difference
/// between the two measures what quantization changes.
#include "octrace/octree/Octree.h"
#include "octrace/render/DiscreteTraversal.h"

namespace octrace {

struct ReferenceRay {
    long double p0[3];   ///< point at parameter 0, octree integer space
    long double dir[3];  ///< change of the point from parameter 0 to 1
    long double tEye;    ///< parameters < tEye are behind the eye
    unsigned sign = 0;   ///< axes whose cells are closed at the top: (lo, hi] (bits as child index)
    bool valid = false;
};

/// The same line as the discrete traversal traces.
ReferenceRay referenceRayFromQuantized(const QuantizedRay& q);
/// The unquantized ray (octree space), with the same main-axis parameterisation.
ReferenceRay referenceRayUnquantized(const dvec3& originOS, const dvec3& directionOS);

/// Thread-safe. counters.nodes counts the nodes whose children were tested. With a cut
/// (Lod.h), stops where it says, as the discrete traversal does. With a filter, a voxel it
/// refuses is passed and the traversal goes on behind it (as traverseDiscrete).
TraversalHit traverseReference(const Octree& tree, const ReferenceRay& ray, TraversalCounters& counters,
                               const LodCut* cut = nullptr, const VoxelFilter* filter = nullptr);

}  // namespace octrace
