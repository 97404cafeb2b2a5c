// A minimal program using octrace's core library from C++: make a field, build the shell
// octree of one isosurface, render it with the discrete ray caster, and check the result
// against the reference traversal. Built and run as a test (octrace_minimal_example), so it
// keeps compiling. Link with octrace::core only: no GDAL, VTK or Qt needed.
#include "octrace/build/AnalyticField.h"   // makeAnalyticField, sampleFunction
#include "octrace/build/OctreeBuilder.h"   // buildShellOctree
#include "octrace/render/Renderer.h"       // makeRenderer, Camera, Frame

#include <cstdio>

int main() {
    using namespace octrace;

    // 1. A scalar field: 0.7 - |p| on 33^3 samples over [-1,1]^3; its iso-0 surface is a sphere.
    //    Readers in octrace::io (NetCDF, NRRD) return the same ScalarField type.
    ScalarField field = makeAnalyticField("sphere", 33);

    // 2. The shell octree at depth 7 (128 voxels per cube edge), built on all cores.
    BuildOptions options;
    options.depth = 7;
    options.iso = 0.0;
    Octree tree = buildShellOctree(field, options);  // throws octrace::Error subclasses
    std::printf("%zu boundary voxels, %.1f bytes each\n", tree.boundaryVoxels(), tree.bytesPerVoxel());

    // 3. A camera framing the surface, and a renderer by name ("full" = discrete integer traversal).
    Camera camera = Camera::framing(tree.occupiedBounds(), 320, 240);
    RenderSettings settings;  // defaults: white background, Lambert shading, all cores
    Frame frame, reference;
    RenderStats stats = makeRenderer("full")->render(tree, camera, settings, frame);
    makeRenderer("reference")->render(tree, camera, settings, reference);

    // 4. Every pixel hits the same voxel as the floating-point oracle.
    std::size_t differing = 0;
    for (std::size_t i = 0; i < frame.hitId.size(); ++i) differing += frame.hitId[i] != reference.hitId[i];
    std::printf("%llu rays, %llu hits, %.2f ms, %zu pixels differ from the reference\n",
                static_cast<unsigned long long>(stats.rays), static_cast<unsigned long long>(stats.hits), stats.renderMs,
                differing);
    return (differing == 0 && stats.hits > 0) ? 0 : 1;
}
