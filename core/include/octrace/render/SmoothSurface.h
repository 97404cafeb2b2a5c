#pragma once
/// @file SmoothSurface.h
/// Smooth surfaces (RenderSettings::surface, SurfaceMode::Smooth): the standard isosurface
/// ray-casting result (Parker et al. 1998; Marmitt et al. 2004) on top of the discrete
/// traversal. The traversal still proposes boundary voxels in visiting order; in each, the
/// camera ray in world coordinates is intersected with the trilinear interpolant of the
/// field's values at the voxel's 8 corners (Octree::corners(), the field's own trilinear
/// values at the lattice corners, as the builder classifies cells by), and the hit point and
/// normal (the interpolant's gradient) come from there. A voxel the ray passes without
/// crossing is refused (VoxelFilter) and the traversal goes on behind it.
///
/// Crossing rule, shared by the fast test and the reference: the ray carries a side, above
/// (value >= iso) or below. At the first proposed voxel it is the side at the ray's entry; the
/// crossing is the first point of the ray in the voxel whose side differs from the carried one
/// (the entry itself when the voxel's own interpolant puts the entry on the other side, which
/// happens where two neighbours' quantized corners disagree on a shared face: no hole opens
/// there); a voxel passed without a crossing hands its exit side on.
///
/// Voxels without corners (code 0: a floor voxel, coarse leaves, nodes drawn whole by a cut)
/// are accepted as boxes.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/RenderSettings.h"

#include <cstdint>

namespace octrace {

/// The test of the proposed voxels of one frame. Thread-safe (the per-ray state is the caller's).
class SmoothSurface {
public:
    SmoothSurface(const Octree& tree, const RenderSettings& settings);
    /// Smooth asked for and the octree has corners: otherwise every voxel is its box.
    bool active() const { return active_; }
    const Octree& tree() const { return tree_; }

    /// One ray's state: the world ray and the side it carries (-1: none yet).
    struct RayState {
        RayState() = default;
        explicit RayState(const Ray& r)
            : world(r), inverse(1.0 / r.direction.x, 1.0 / r.direction.y, 1.0 / r.direction.z) {}
        Ray world;
        dvec3 inverse{0.0};  ///< 1 / world.direction per axis (the box clip's slabs)
        int side = -1;
    };
    /// The fast test: the interpolant along the ray is a cubic in the distance; its extrema
    /// split the ray's span in the voxel into monotone pieces, the first piece whose end lies
    /// on the other side holds the crossing, found by Newton's method from the regula falsi
    /// point, kept inside the bracket, to 1e-7 of a voxel. Fills hit.smooth, distance, normal
    /// when it accepts. Nodes drawn whole, coarse leaves and voxels without corners are accepted
    /// as they are.
    bool test(RayState& ray, TraversalHit& hit) const;
    /// test() of one voxel for `count` rays (1 .. 32) that meet it (a packet's lanes): hit k is
    /// *hits[k], with the voxel's fields set alike in all, ray k *rays[k]. Returns the rays
    /// accepted (bit k); every ray's result, hit and carried side are test()'s, bit for bit. With
    /// AVX-512, the voxel's corners are decoded once and the box clip, the cubic and the first
    /// steps of the search run eight rays at a time; the rest of the search, for the rays that
    /// need it, and the hit are test()'s own code.
    unsigned testLanes(RayState* const* rays, TraversalHit* const* hits, unsigned count) const;
    /// The reference test, written independently of test(): the trilinear interpolant evaluated
    /// directly (no polynomial) at kReferenceSteps equal steps over the ray's span in the voxel,
    /// the first step that changes side bisected to 1e-12 of a voxel, in float64.
    bool testReference(RayState& ray, TraversalHit& hit) const;
    static constexpr int kReferenceSteps = 256;

    /// A filter for the traversals (DiscreteTraversal.h) over `ray` with test() or
    /// testReference(); empty when not active().
    VoxelFilter filter(RayState& ray, bool reference = false) const;

private:
    /// The voxel's box clipped to the ray (in front of the eye): entry distance t0, length
    /// in voxels `span`, the entry in voxel coordinates [0,1]^3; false when the ray misses it.
    bool clip(const RayState& ray, const ivec3& cell, double& t0, double& span, dvec3& entry) const;
    /// The shared part of test() and testReference(): the voxel's corners and the ray's span in
    /// it, handed to `search`, which finds the crossing.
    template <class Search>
    bool testWith(RayState& ray, TraversalHit& hit, const Search& search) const;
    bool accept(const RayState& ray, TraversalHit& hit, const double d[8], double t0, const dvec3& entry, double u) const;
    const Octree& tree_;
    bool active_ = false;
    double inverseVoxel_ = 1.0;  ///< 1 / the voxel's side
};

}  // namespace octrace
