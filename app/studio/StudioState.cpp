#include "StudioState.h"

#include "Input.h"
#include "SurfaceOptions.h"

#include "octrace/io/CityReader.h"

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

bool colourGiven(const StudioState& state) { return state.colour != StudioState().colour; }

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

cli::SurfaceArgs surfaceArgs(const StudioState& state) {
    cli::SurfaceArgs a;
    a.input = state.input;
    a.request.variable = state.variable;
    a.request.time = state.time;
    a.request.series = state.series;
    a.iso = state.iso;
    a.depth = state.depth;
    a.colour = state.colour;
    a.colourGiven = colourGiven(state);
    a.colormap = state.colormap;
    if (!state.window.empty()) {
        a.windowName = state.window;
        a.window = cli::displayWindow(state.window);
    }
    return a;
}

RenderSettings renderSettingsFor(const StudioState& state, bool transparent, const ValueWindow& window, bool invertedGrey) {
    RenderSettings rs;
    vec4 bg = state.background;
    if (transparent) bg.a = 0.0f;
    rs.background = cli::displayToLinear(bg);
    cli::Surface look;
    look.window = window;
    look.invertedGrey = invertedGrey;
    cli::applyColour(surfaceArgs(state), look, rs);
    rs.lightCamera = state.light;
    return rs;
}

std::vector<std::string> renderArguments(const StudioState& state, const Camera& camera, double iso,
                                         const std::string& output) {
    std::vector<std::string> args{state.input};
    if (!state.variable.empty()) args.insert(args.end(), {"--var", state.variable});
    if (!state.time.empty()) args.insert(args.end(), {"--time", state.time});
    if (!state.series.empty()) args.insert(args.end(), {"--series", state.series});
    // An octree file fixes the iso value and the depth; a city model has no iso value.
    if (!cli::isOctreeInput(state.input) && !io::isCityInput(state.input)) args.insert(args.end(), {"--iso", number(iso)});
    if (!cli::isOctreeInput(state.input)) args.insert(args.end(), {"--depth", std::to_string(state.depth)});
    args.insert(args.end(), {"--renderer", state.renderer,
                             "--size", std::to_string(camera.width) + "x" + std::to_string(camera.height),
                             "--camera-pos", triple(camera.position.x, camera.position.y, camera.position.z),
                             "--look-at", triple(camera.lookAt.x, camera.lookAt.y, camera.lookAt.z),
                             "--up", triple(camera.up.x, camera.up.y, camera.up.z),
                             "--fov", number(camera.fovYDegrees),
                             "--light", triple(state.light.x, state.light.y, state.light.z)});
    if (colourGiven(state)) args.insert(args.end(), {"--colour", triple(state.colour.r, state.colour.g, state.colour.b)});
    if (!state.colormap.empty()) args.insert(args.end(), {"--colormap", state.colormap});
    if (!state.window.empty()) args.insert(args.end(), {"--window", state.window});
    const vec4& b = state.background;
    args.insert(args.end(), {"--background", triple(b.r, b.g, b.b) + "," + number(state.transparent ? 0.0 : b.a)});
    args.insert(args.end(), {"-o", output});
    return args;
}

}  // namespace octrace::studio
