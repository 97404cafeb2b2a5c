#pragma once
/// @file AutoDepth.h
/// The octree depth that fits the data (the `depth` setting's default, auto): for a sampled
/// field, the shallowest depth whose voxel is no larger than the field's median sample spacing
/// along each axis; for geometry (cities, sphere scenes), the depth whose voxel is about one
/// pixel of a view. The memory budget's cap is the caller's: it knows the budget and what the
/// build needs (estimateBuildMemory in OctreeBuilder.h). Pure functions, thread-safe.
#include "octrace/build/ScalarField.h"

#include <string>

namespace octrace {

struct DepthChoice {
    int depth = 0;       ///< 1 .. Octree::kMaxDepth; 0 none chosen yet
    std::string reason;  ///< why, for the log and `info`: "voxel 1.4 mm <= median spacing 1.41 mm along x"
};

/// The median distance between neighbouring samples along grid axis `axis` (0..2), in world
/// units: a uniform axis's spacing, a rectilinear axis's median step. An uneven ocean depth
/// axis is judged here after its vertical scale (its coordinates are world z), not by its
/// finest level. Throws Error for an axis with fewer than 2 samples.
double medianSpacing(const ScalarField& f, int axis);

/// The side of the cube that an octree of `f` spans: the largest extent of its world box
/// (OctreeBuilder.h).
double cubeSideOf(const ScalarField& f);

/// The shallowest depth in 1..Octree::kMaxDepth whose voxel, cubeSide / 2^depth, is no larger
/// than `voxel` (up to a relative 1e-9, so that a grid of 2^n cells gets depth n exactly);
/// kMaxDepth when none is.
int shallowestDepthFor(double cubeSide, double voxel);

/// The shallowest depth whose voxel is no larger than the median spacing of `f` along each of
/// its axes (a planar field's single level is not an axis). The reason names the axis that
/// decides, in the field's world units (km on a geographic grid, mm for a patient volume).
DepthChoice depthForField(const ScalarField& f);

/// The depth whose voxel, cubeSide / 2^depth, is nearest to `pixel` world units (one pixel of
/// a view at its look-at point) in ratio, i.e. between 1/sqrt(2) and sqrt(2) pixels; clamped to
/// 1..Octree::kMaxDepth. `unit` ("m", "angstrom", "" none) is for the reason only.
DepthChoice depthForPixel(double cubeSide, double pixel, const std::string& unit = "");

}  // namespace octrace
