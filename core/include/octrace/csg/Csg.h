#pragma once
/// @file Csg.h
/// Union, intersection and difference of volume octrees (build/Volume.h) and primitive
/// solids (csg/Solid.h), voxelized on the fly.
///
/// The result is a volume octree on a common cube: the tree operand's cube when the other is a
/// solid; for two trees, their common cube when they share it (depth: the larger), else the
/// smallest cube holding both at a depth whose voxels are no larger than the finer operand's
/// (at most Octree::kMaxDepth). A tree operand is sampled at each result voxel's centre; a
/// solid classifies each voxel by its 8 corners (all inside: interior, none: empty, else a
/// boundary voxel with the solid's outward normal at the voxel's centre). Per voxel:
///   union: interior if either is; a boundary voxel of one that the other does not hold keeps
///          its normal; boundary in both: the normalised sum of the two normals;
///   intersection: interior if both are; boundary where one is boundary and the other holds it;
///   difference A - B: A intersected with the complement of B, whose boundary voxels have B's
///          normals reversed: the cut faces get the normals of the cutting solid.
/// Values and colours (Octree::voxelValues(), Octree::colours(), when an operand that is not
/// subtracted has them) come from the first operand holding the voxel; a voxel cut out of an
/// operand's interior term takes those of the nearest voxel that has them (resample values from
/// the field with fillVoxelValues, OctreeBuilder.h, where it is known). Baked light is never
/// kept: it belongs to shells; bake the result's shell.
/// Then an interior voxel next to an empty cell or the cube's face becomes a boundary voxel
/// pointing out towards them, so the result keeps the invariant of Volume.h and its shell
/// (extractShell) is closed. Union and intersection are commutative: the same octree whichever
/// operand comes first.
#include "octrace/csg/Solid.h"
#include "octrace/octree/Octree.h"

#include <string>

namespace octrace {

enum class CsgOp { Union, Intersection, Difference };

/// "union", "intersection", "difference" (also "intersect", "minus"); UsageError otherwise.
CsgOp parseCsgOp(const std::string& name);
const char* csgOpName(CsgOp op);

/// A volume octree (not owned; a shell octree is refused) or a primitive solid.
struct CsgOperand {
    const Octree* tree = nullptr;
    Solid solid;
    static CsgOperand of(const Octree& t) { return {&t, Solid{}}; }
    static CsgOperand of(const Solid& s) { return {nullptr, s}; }
};

/// A OP B as a volume octree. Throws UsageError when neither operand is an octree (no cube to
/// voxelize on) or one is a shell octree, EmptyResultError when the result is empty.
Octree csg(const CsgOperand& a, CsgOp op, const CsgOperand& b);

}  // namespace octrace
