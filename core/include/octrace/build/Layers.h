#pragma once
/// @file Layers.h
/// Several surfaces in one shell octree, told apart by their material (Octree::voxelMaterials):
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

/// Sets every voxel of `tree` to `material`.
void setMaterial(Octree& tree, VoxelMaterial material);

/// The union of two shell octrees with the same cube and depth: every boundary voxel of
/// either; where both have one, `top`'s is kept. Each voxel keeps its normal, its material
/// and its value (NaN when its octree has no voxelValues; the result has voxelValues when
/// either has). Provenance (field name, iso, source) is `top`'s. Throws UsageError when the
/// cubes or depths differ or either is not a shell octree.
Octree mergeShells(const Octree& top, const Octree& under);

}  // namespace octrace
