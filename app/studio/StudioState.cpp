#include "StudioState.h"

#include "SurfaceOptions.h"

#include <cstdio>

namespace octrace::studio {
namespace {

std::string number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string triple(double a, double b, double c) { return number(a) + "," + number(b) + "," + number(c); }

}  // namespace

Camera cameraFor(const StudioState& state, const Box3& surfaceBounds, int width, int height) {
    // As `octrace render`: the framing first, then the camera options over it.
    Camera cam = Camera::framing(surfaceBounds, width, height, state.fov);
    if (state.cameraSet) {
        cam.position = state.position;
        cam.lookAt = state.lookAt;
        cam.up = state.up;
    }
    return cam;
}

RenderSettings renderSettingsFor(const StudioState& state, bool transparent) {
    RenderSettings rs;
    vec4 bg = state.background;
    if (transparent) bg.a = 0.0f;
    rs.background = cli::displayToLinear(bg);
    cli::SurfaceArgs a;
    a.colour = state.colour;
    a.colormap = state.colormap;
    cli::applyColour(a, rs);
    rs.lightCamera = state.light;
    return rs;
}

std::vector<std::string> renderArguments(const StudioState& state, const Camera& camera, double iso,
                                         const std::string& output) {
    std::vector<std::string> args{state.input};
    if (!state.variable.empty()) args.insert(args.end(), {"--var", state.variable});
    if (!state.time.empty()) args.insert(args.end(), {"--time", state.time});
    if (!state.series.empty()) args.insert(args.end(), {"--series", state.series});
    args.insert(args.end(), {"--iso", number(iso), "--depth", std::to_string(state.depth), "--renderer", state.renderer,
                             "--size", std::to_string(camera.width) + "x" + std::to_string(camera.height),
                             "--camera-pos", triple(camera.position.x, camera.position.y, camera.position.z),
                             "--look-at", triple(camera.lookAt.x, camera.lookAt.y, camera.lookAt.z),
                             "--up", triple(camera.up.x, camera.up.y, camera.up.z),
                             "--fov", number(camera.fovYDegrees),
                             "--light", triple(state.light.x, state.light.y, state.light.z),
                             "--colour", triple(state.colour.r, state.colour.g, state.colour.b)});
    if (!state.colormap.empty()) args.insert(args.end(), {"--colormap", state.colormap});
    const vec4& b = state.background;
    args.insert(args.end(), {"--background", triple(b.r, b.g, b.b) + "," + number(state.transparent ? 0.0 : b.a)});
    args.insert(args.end(), {"-o", output});
    return args;
}

}  // namespace octrace::studio
