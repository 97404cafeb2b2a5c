#include "octrace/model/Render.h"

#include "octrace/render/Renderer.h"
#include "octrace/util/Error.h"

namespace octrace::model {

CoherenceSettings tableCoherence() {
    CoherenceSettings c;
    c.colourTolerance = float(opt::colourTolerance.defaultValue);
    c.branchUp = int(opt::branchUp.defaultValue);
    c.miss = opt::missCoherence.defaultChoice() == "on";
    return c;
}

SphereShading tableSphereShading() {
    SphereShading s;
    s.samples = int(opt::samples.defaultValue);
    s.bounces = int(opt::bounces.defaultValue);
    return s;
}

Camera frameCamera(const RenderSpec& spec, const Box3& bounds) {
    Camera cam = Camera::framing(bounds, spec.width, spec.height, spec.fov);
    if (spec.lookAt) cam.lookAt = *spec.lookAt;
    if (spec.up) cam.up = *spec.up;
    if (spec.cameraPos) cam.position = *spec.cameraPos;
    else if (spec.lookAt) cam.position = cam.lookAt + (Camera::framing(bounds, spec.width, spec.height, spec.fov).position - bounds.centre());
    if (spec.ortho) {
        cam.validate();
        cam.frameOrthographic(bounds);
        if (spec.cameraPos) cam.position = *spec.cameraPos;  // the user's view plane, even if it cuts the surface
        if (spec.orthoHeight) cam.orthoHeight = *spec.orthoHeight;
    }
    cam.validate();
    return cam;
}

RenderSettings renderSettings(const SurfaceSpec& surfaceSpec, const Surface& surface, const RenderSpec& spec) {
    RenderSettings rs;
    rs.threads = surfaceSpec.threads;
    rs.background = displayToLinear(spec.background);
    applyColour(surfaceSpec, surface, rs);
    if (spec.light) rs.lightCamera = *spec.light;
    applyLighting(surfaceSpec, rs);
    rs.coherence = spec.coherence;
    rs.detail = spec.detail;
    rs.spheres = spec.spheres;
    return rs;
}

RenderStats renderFrame(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                        const std::string& renderer, Frame& frame) {
    const RendererName name = resolveRendererName(renderer);
    const std::unique_ptr<Renderer> r = makeRenderer(name.renderer);
    if (!r->drawsVoxels()) throw UsageError("renderer " + renderer + " does not draw voxel octrees");
    RenderSettings s = settings;
    name.applyTo(s);
    return r->render(tree, camera, s, frame);
}

}  // namespace octrace::model
