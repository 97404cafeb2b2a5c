#pragma once
/// @file Verify.h
/// A pipeline step of every front end: how far a rendered frame is from the floating-point
/// reference traversal (what `octrace render --verify` reports). No argv, no Qt.
#include "octrace/octree/Octree.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Frame.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/render/Renderer.h"

#include <cstdint>
#include <optional>

namespace octrace::model {

struct Verification {
    /// Traced pixels whose hit voxel (or hit/miss) differs from the reference; pixels filled
    /// by colour coherence are not traced and are judged by the image difference instead.
    std::uint64_t mismatchedPixels = 0;
    double psnrDb = 0.0, maxChannelError = 0.0;
    double referenceMs = 0.0, referenceUsPerRay = 0.0;  ///< the reference's fastest of `repeat`
    /// Pixels where the reference on the unquantized rays hits another voxel than on the
    /// quantized ones: what quantizing the ray changes.
    std::uint64_t unquantizedMismatchedPixels = 0;
    /// Of the pixels hit by either the frame or the reference, the share hit by both (for
    /// renderers that do not trace the reference's rays: direct), and the largest depth
    /// difference where both hit, in voxel diagonals.
    double hitAgreement = 1.0, depthMaxErrorDiagonals = 0.0;
    /// With a multi-resolution cut (settings.detail.lodPixels or level): the frame against the same
    /// renderer down to the voxels.
    std::optional<ImageDifference> levelOfDetail;
};

/// Renders `tree` again with the reference traversal (`repeat` times, the fastest timed), with
/// the reference on unquantized rays, and (with a multi-resolution cut) with `renderer` exact,
/// and compares `frame`, which `renderer` drew with `settings`, against them.
Verification verifyFrame(const Octree& tree, const Camera& camera, const RenderSettings& settings, const Frame& frame,
                         const Renderer& renderer, int repeat = 1);

}  // namespace octrace::model
