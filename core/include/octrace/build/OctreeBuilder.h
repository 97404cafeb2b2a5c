#pragma once
/// @file OctreeBuilder.h
/// Builds the shell octree of an isosurface of a ScalarField, top-down, without a dense
/// 2^depth array: memory grows with the number of boundary voxels.
///
/// The octree's cube is centred on the field's world bounding box, with the box's largest
/// extent as its side. A cell at the
/// finest level is a boundary voxel when the trilinear field at its 8 corners has some corner
/// >= iso and some < iso; it is masked (never boundary) when one of its corners lies outside
/// the grid or uses a masked sample. Boundary voxels carry the normalised negative gradient
/// (pointing towards lower values) taken in world space.
#include "octrace/build/ScalarField.h"
#include "octrace/octree/Octree.h"

#include <functional>

namespace octrace {

struct BuildOptions {
    int depth = 8;          ///< 1 .. Octree::kMaxDepth
    double iso = 0.0;
    int threads = 0;        ///< 0 = all cores, 1 = serial (same result either way)
    /// Called now and then with a fraction in [0,1]; may be empty. It runs on worker threads,
    /// one call at a time, with fractions that never decrease and end at 1.
    std::function<void(double)> progress;
};

struct BuildReport {
    double buildMs = 0.0;
    std::size_t boundaryVoxels = 0;
    std::size_t nodes = 0;
};

/// Throws UsageError for a depth out of range, EmptyResultError when iso is outside the valid
/// value range or no cell straddles it. The field must have passed validate().
Octree buildShellOctree(const ScalarField& field, const BuildOptions& options, BuildReport* report = nullptr);

}  // namespace octrace
