#pragma once
/// @file CityVoxelizer.h
/// Builds the shell octree of a city model (CityModel.h) top-down from its triangles, without
/// a dense 2^depth array: a node is split only where triangles cross it, so memory grows with
/// the number of boundary voxels.
///
/// A voxel is a boundary voxel when a triangle meets its closed box. Its normal is that of the
/// triangle whose plane passes nearest its centre (ties: the first triangle); its colour is the
/// texture's at the voxel's centre for terrain where the texture has data, else that
/// triangle's object's colour (Octree::colours()). The cube is centred on the model's bounding
/// box, with the box's largest extent as its side. With a terrain depth, terrain-only nodes
/// at that level are coarse leaves, given a normal and colour the same way from their centre.
#include "octrace/build/CityModel.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/octree/Octree.h"

namespace octrace {

struct CityBuildOptions {
    int depth = 10;   ///< octree depth, 1 .. Octree::kMaxDepth
    int threads = 0;  ///< 0 = all cores, 1 = serial (same result either way)
    /// Per-region depth (paper A's city map): a node at this level or deeper that only
    /// terrain triangles cross becomes a coarse leaf (Octree.h) instead of being split down
    /// to `depth`; buildings (and terrain in nodes they share with buildings) go to `depth`.
    /// 0 (default) or >= depth: every triangle to `depth`.
    int terrainDepth = 0;
};

/// Throws UsageError for a depth or terrain depth out of range, EmptyResultError when the model has no
/// triangle with area. The result's crs and source are the model's.
Octree voxelizeCity(const CityModel& model, const CityBuildOptions& options, BuildReport* report = nullptr);

}  // namespace octrace
