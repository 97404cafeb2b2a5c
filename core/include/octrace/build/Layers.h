#pragma once
/// @file Layers.h
/// Several surfaces in one shell octree, told apart by their material (Octree::voxelMaterials()):
/// an isosurface with the sea floor and land under it. Each layer is built on its own over the
/// same cube and depth (buildShellOctree of fields with the same grid), then merged, so that
/// every renderer draws them together like any other octree.
#include "octrace/build/ScalarField.h"
#include "octrace/octree/Octree.h"

namespace octrace {

/// The solid under and beside the valid samples, as a field whose 0.5 isosurface is the sea
/// floor and the coasts: 1 at masked (land, sea floor) samples, 0 at valid ones, every sample
/// valid, the same grid and geometry as `field`. Throws EmptyResultError when `field` has no
/// masked sample (nothing to draw).
ScalarField solidFromMask(const ScalarField& field);

/// Extends every water column down to the bottom of the grid: each masked sample that lies
/// under a valid one in its column (grid axis z, which points up on geographic grids) takes
/// the value of the deepest valid sample above it and becomes valid; columns with no valid
/// sample (land) stay masked. For cutting the field by a finer sea floor than its own mask
/// (a relief solid, csg/Relief.h) instead of the grid's staircase. Returns the number of
/// samples filled. Throws UsageError for a field that is not geographic.
std::size_t extendColumnsDown(ScalarField& field);

/// Sets every voxel of `tree` to `material`.
void setMaterial(Octree& tree, VoxelMaterial material);

/// The union of two shell octrees with the same cube and depth: every boundary voxel of
/// either; where both have one, `top`'s is kept. Each voxel keeps its normal, its material
/// and its value (NaN when its octree has no voxelValues; the result has voxelValues when
/// either has). Provenance (field name, iso, source) is `top`'s. Throws UsageError when the
/// cubes or depths differ or either is not a shell octree.
Octree mergeShells(const Octree& top, const Octree& under);

}  // namespace octrace
