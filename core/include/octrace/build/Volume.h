#pragma once
/// @file Volume.h
/// The volume form of the octree (OctreeForm::Volume): the solid with its interior kept, as
/// buildOctree makes it from a field and the CSG operations (csg/Csg.h) combine it.
///
/// Layout (Octree.h): an octant wholly inside the solid is an interior *term* (term bit set,
/// a slot in `nodes` with childMask 0); at level depth-1 a term bit marks an *interior voxel*
/// (a slot in `voxels`, normal unused); a voxel without it is a *boundary voxel* with a unit
/// normal pointing out of the solid. Invariant kept by every producer: a voxel of the solid
/// whose face neighbour is not in the solid (or lies outside the cube) is a boundary voxel; so
/// the boundary voxels alone (extractShell) draw the solid closed, with caps where it was cut.
#include "octrace/octree/Octree.h"

#include <cstdint>

namespace octrace {

struct VoxelCount {
    std::uint64_t interior = 0;  ///< interior voxels, terms counted by the voxels they hold
    std::uint64_t boundary = 0;  ///< boundary voxels
    /// Volume estimate in voxels: a boundary voxel is cut by the surface, about half inside.
    double volume() const { return double(interior) + 0.5 * double(boundary); }
};

/// What a voxel cell is in a volume octree (a shell octree: Boundary or Empty).
enum class CellState : std::uint8_t { Empty, Interior, Boundary };
/// The state of cell (i,j,k) (cell space; outside the cube: Empty) and, for a boundary voxel,
/// its index in `voxels` (else 0xFFFFFFFF). O(depth).
CellState cellState(const Octree& tree, const ivec3& cell, std::uint32_t* voxel = nullptr);
/// As cellState, but `slot` is the voxel slot of interior voxels too (at level depth-1, where
/// they have one); 0xFFFFFFFF for an empty cell or one inside an interior term.
CellState cellSlot(const Octree& tree, const ivec3& cell, std::uint32_t& slot);

/// Counts the voxels of a volume octree (a shell octree: its boundary voxels only).
VoxelCount countVoxels(const Octree& tree);

/// The shell form of a volume octree: its boundary voxels with their normals, voxel values and
/// colours (when it has them), nothing else
/// (same cube, depth and provenance; terms and interior voxels dropped). A shell octree is
/// copied as it is. Throws EmptyResultError when the solid has no boundary voxel.
Octree extractShell(const Octree& volume);


}  // namespace octrace
