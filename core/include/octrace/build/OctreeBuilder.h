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

#include <cstdint>
#include <functional>
#include <vector>

namespace octrace {

struct BuildOptions {
    int depth = 8;          ///< 1 .. Octree::kMaxDepth
    double iso = 0.0;
    int threads = 0;        ///< 0 = all cores, 1 = serial (same result either way)
    /// Called now and then with a fraction in [0,1]; may be empty. It runs on worker threads,
    /// one call at a time, with fractions that never decrease and end at 1.
    std::function<void(double)> progress;
    /// Asked now and then, from worker threads and possibly concurrently (so it must be
    /// thread-safe, e.g. read a std::atomic<bool>); may be empty. When it returns true the
    /// build stops within a few thousand cells and throws CancelledError. For interactive
    /// programs (the studio's Cancel button).
    std::function<bool()> cancelled;
    /// Memory budget in bytes for the field and the build together; 0 = no limit. With one,
    /// the build first estimates its peak (estimateBuildMemory) and refuses a depth whose
    /// estimate exceeds the budget, naming the largest depth that fits; then it counts every
    /// buffer it allocates and stops as soon as they would go over (both throw LimitError),
    /// so an estimate that was too low still ends with a message instead of the OOM killer.
    std::uint64_t memoryBudget = 0;
    /// Also fill Octree::voxelValues(): per boundary voxel the trilinear field one voxel edge
    /// inside the surface (from the voxel's centre against its normal, towards values >= iso),
    /// or at the centre where that point is masked or outside the grid. What a display window
    /// colours by: the tissue under the surface rather than the iso value itself.
    bool voxelValues = false;
    /// Also fill Octree::corners(): per boundary voxel the trilinear field at its 8 corners, the
    /// values it was classified by, relative to the iso value and quantized (encodeCorners,
    /// render/SmoothSurface.h), for smooth surfaces. Shell form only (the volume form's caps have
    /// no crossing to find): ignored for the volume form. 8 bytes per voxel.
    bool corners = false;
    /// buildOctree only: the shell (boundary voxels) or the volume form (the solid bounded by
    /// the isosurface, interior kept: build/Volume.h).
    OctreeForm form = OctreeForm::Shell;
    /// Volume form: the solid is where the field is below the iso value (else at or above it).
    bool insideBelow = false;
};

/// What buildShellOctree allocates at one depth, at its peak (bytes, allocated rather than
/// resident: the figures err on the high side).
struct BuildMemoryEstimate {
    int depth = 0;
    std::uint64_t fieldBytes = 0;    ///< the field itself (samples, mask, axes): alive during the build
    std::uint64_t samplerBytes = 0;  ///< the builder's NaN-masked copy of the samples, its min/max pyramid, axis tables
    double boundaryVoxels = 0.0;     ///< estimated boundary voxels at this depth
    std::uint64_t octreeBytes = 0;   ///< the subtrees' buffers and the joined octree (both exist while joining)
    /// The per-voxel attributes the build fills after joining, as BuildOptions asks for them:
    /// corner values (8 bytes a voxel), voxel values (4 bytes), and the list of the voxels'
    /// cells they are sampled at (12 bytes, while filling). Counted on top of octreeBytes,
    /// although the join's second copy is gone by then (errs on the high side).
    std::uint64_t attributeBytes = 0;
    std::uint64_t total() const { return fieldBytes + samplerBytes + octreeBytes + attributeBytes; }
};

/// Estimates the peak memory of buildShellOctree(field, {depth, iso}) for every depth
/// 1..maxDepth (element depth-1). The field and the sampler are counted exactly. Boundary
/// voxels are counted exactly up to depth 6 by building those small octrees; deeper, the
/// count is extrapolated with the growth rate measured between depths 5 and 6 (at least 4:
/// a smooth surface's voxels quadruple per level) down to the grid's own resolution, then
/// by 4 per level, plus 25 %. At depths 7 to 11 this was 1.25 times the true count on the
/// analytic fields and 1.3 to 2.4 times on the CT, MRI and ocean data of ../shared/data
/// (docs/dev/reliability.md); where it is too low (a surface finer than depth 6 shows), the
/// running check of buildShellOctree stops the build at the budget.
/// Throws as buildShellOctree (depth or iso out of range, empty grid); a surface that only
/// appears deeper than depth 6 counts as one voxel there. Thread-safe.
std::vector<BuildMemoryEstimate> estimateBuildMemory(const ScalarField& field, double iso, int maxDepth, int threads = 0);
/// The same for the build `options` describes: depths 1..options.depth at options.iso with
/// options.threads, counting the per-voxel attributes it asks for (BuildOptions::corners in
/// the shell form, BuildOptions::voxelValues) in attributeBytes, as buildOctree's own check of
/// BuildOptions::memoryBudget does.
std::vector<BuildMemoryEstimate> estimateBuildMemory(const ScalarField& field, const BuildOptions& options);

struct BuildReport {
    double buildMs = 0.0;
    std::size_t boundaryVoxels = 0;
    std::size_t nodes = 0;
};

/// Throws UsageError for a depth out of range, EmptyResultError when iso is outside the valid
/// value range or no cell straddles it, LimitError when the memory budget is too small (see
/// BuildOptions::memoryBudget), CancelledError when BuildOptions::cancelled says so. The field must have passed validate().
Octree buildShellOctree(const ScalarField& field, const BuildOptions& options, BuildReport* report = nullptr);

/// The trilinear value of `field` at the world centre of every boundary voxel of `tree`, by
/// voxel index (for Octree::voxelValues(): colour a surface by a second variable). NaN where the
/// interpolation uses a masked sample or the centre lies outside the field's grid. The field
/// must pass validate() (else FileError). Thread-safe; `threads` as BuildOptions::threads.
std::vector<float> sampleAtVoxels(const Octree& tree, const ScalarField& field, int threads = 0);
/// Fills `tree.voxelValues` from `field` as BuildOptions::voxelValues does (the field one voxel
/// edge in from each voxel's centre against its normal; at the centre where that is masked or
/// outside; the tree's iso value where both are), for every voxel slot: after a CSG operation
/// (csg/Csg.h) the cut faces get the field's value where they are. The field must pass
/// validate() (else FileError). Thread-safe; `threads` as BuildOptions::threads.
void fillVoxelValues(Octree& tree, const ScalarField& field, int threads = 0);
/// Fills Octree::corners() from `field` as BuildOptions::corners does, for an octree built from
/// that field at its iso value without them (a shell: the volume form keeps none). For a
/// surface whose drawing is decided after the build (the Python module's, docs/dev/smooth-surfaces.md).
/// The field must pass validate() (else FileError). Thread-safe; `threads` as BuildOptions::threads.
void fillCorners(Octree& tree, const ScalarField& field, int threads = 0);
/// As buildShellOctree, in the form options.form. The volume form, built top-down from the
/// same min/max pyramid (no dense array either; interior octants become terms at the highest
/// level the pyramid proves them interior): a cell whose 8 corners are inside the solid
/// (value >= iso, or < iso with insideBelow; none masked) is an interior voxel; a cell that
/// straddles the iso value is a boundary voxel with the field's normal pointing out of the
/// solid; an inside cell next to a masked cell, a cell outside the grid or the cube's face is
/// a boundary voxel of a *cap*, its normal pointing out towards them. So every voxel of the
/// solid with an empty face neighbour is a boundary voxel, and extractShell draws the solid
/// closed. BuildReport::boundaryVoxels counts boundary voxels only. @throws InputError for a
/// planar field (a 2-D map has no surface).
Octree buildOctree(const ScalarField& field, const BuildOptions& options, BuildReport* report = nullptr);

}  // namespace octrace
