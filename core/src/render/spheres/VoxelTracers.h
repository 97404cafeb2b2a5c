#pragma once
// Private to core: samet and beam on the voxel octree (the sphere versions are in
// SphereRenderers.h). How they work: docs/dev/spheres.md, "On the voxel octree".
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/Renderer.h"

#include <string>

namespace octrace::detail {

enum class VoxelTracer { Samet, Beam };

/// Renders the voxel octree with the given tracer: the same hit voxel per pixel as the
/// reference traversal on the same quantized rays, shaded as every ray caster shades. Throws
/// UsageError when a multi-resolution cut is asked for.
RenderStats renderVoxelTracer(VoxelTracer tracer, const std::string& name, const Octree& tree, const Camera& camera,
                              const RenderSettings& settings, Frame& frame);

}  // namespace octrace::detail
