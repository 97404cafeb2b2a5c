#pragma once
// The face neighbours of an octree's voxels in the .oct file's voxel order (internal): what the
// 'NORM' chunk's prediction reads (docs/dev/octree-files.md).
#include "octrace/octree/Octree.h"

#include <array>
#include <cstdint>
#include <vector>

namespace octrace::io::detail {

constexpr std::uint32_t kNoNeighbour = 0xFFFFFFFFu;

/// Per voxel, in breadth-first order (level by level, children in child-index order: at the
/// voxel level, Morton order): the breadth-first index of the voxel at -x, -y and -z (elements
/// 0, 1, 2), kNoNeighbour where that cell holds no voxel or lies outside the cube.
/// Found level by level from the root: a child's neighbour at -a is its sibling when the child is
/// on the high side of axis a, else the high-side child of its parent's neighbour at -a. Every
/// neighbour precedes the voxel (a smaller Morton code). Every voxel lies at the voxel level: a
/// tree with coarse leaves (which files cannot hold: encodeOctreeFile refuses it first) would
/// leave them out.
std::vector<std::array<std::uint32_t, 3>> voxelNeighbours(const Octree& tree);

}  // namespace octrace::io::detail
