#include "StudioState.h"

#include "octrace/model/Input.h"
#include "octrace/model/Settings.h"
#include "octrace/model/Surface.h"

#include "octrace/io/CityReader.h"
#include "octrace/render/Renderer.h"

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

std::span<const Binding> bindings() {
    using E = Binding::Effect;
    static const Binding table[] = {
        {&model::opt::colourCoherence, &StudioState::colourCoherence, E::Render, true},
        {&model::opt::colourTolerance, &StudioState::colourTolerance, E::Render, true},
        {&model::opt::colourFillBackground, &StudioState::colourFillsBackground, E::Render, true},
        {&model::opt::branchUp, &StudioState::branchUp, E::Render, true},
        {&model::opt::missCoherence, &StudioState::missCoherence, E::Render, true},
        {&model::opt::fov, &StudioState::fov, E::Render},
        {&model::opt::ambient, &StudioState::ambient, E::Render},
        {&model::opt::bakeAo, &StudioState::bakeAo, E::Rebuild},
        {&model::opt::bakeShadows, &StudioState::bakeShadows, E::Rebuild},
        {&model::opt::shadows, &StudioState::shadows, E::Render},
        {&model::opt::width, &StudioState::exportWidth, E::Render},
        {&model::opt::height, &StudioState::exportHeight, E::Render},
        {&model::opt::figure, &StudioState::figure, E::Render},
        {&model::opt::dpi, &StudioState::dpi, E::Render},
        {&model::opt::scaleBar, &StudioState::scaleBar, E::Render},
    };
    return table;
}

std::span<const model::Option* const> textSettings() {
    static const model::Option* const table[] = {&model::opt::region,   &model::opt::depthRange, &model::opt::verticalScale,
                                                 &model::opt::mapProjection, &model::opt::volume, &model::opt::colourBy,
                                                 &model::opt::floor, &model::opt::surface};
    return table;
}

SettingEffect settingEffect(const model::Option& o) {
    if (model::settingPart(o) == model::SettingPart::Request) return SettingEffect::Reload;
    return model::shadingSetting(o) ? SettingEffect::Render : SettingEffect::Rebuild;
}

void checkSetting(const model::Option& o, const std::string& text) {
    model::SurfaceSpec scratch;
    model::applySetting(o, text, {.surface = &scratch});
}

bool colourGiven(const StudioState& state) { return state.colour != StudioState().colour; }

model::RenderSpec renderSpec(const StudioState& state, int width, int height) {
    model::RenderSpec r;
    r.renderer = state.renderer;
    r.width = width;
    r.height = height;
    r.fov = state.fov;
    if (state.cameraSet) {
        r.cameraPos = state.position;
        r.lookAt = state.lookAt;
        r.up = state.up;
    }
    r.background = state.background;
    r.light = state.light;
    r.coherence.colour = state.colourCoherence;
    r.coherence.colourTolerance = state.colourTolerance;
    r.coherence.colourFillsBackground = state.colourFillsBackground;
    r.coherence.branchUp = state.branchUp;
    r.coherence.miss = state.missCoherence;
    return r;
}

Camera cameraFor(const StudioState& state, const Box3& surfaceBounds, model::SceneView view, int width, int height) {
    return model::frameCamera(renderSpec(state, width, height), surfaceBounds, view);
}

model::SurfaceSpec surfaceArgs(const StudioState& state) {
    model::SurfaceSpec a;
    a.colours = true;  // the studio colours its surface (window, colour map), as render does
    a.input = state.input;
    a.request.variable = state.variable;
    a.request.time = state.time;
    a.request.series = state.series;
    for (const auto& [key, text] : state.settings)
        if (const model::Option* o = model::findOption(key)) model::applySetting(*o, text, {.surface = &a});
    a.iso = state.iso;
    a.depth = state.depth;
    a.colour = state.colour;
    a.colourGiven = colourGiven(state);
    a.colormap = state.colormap;
    if (!state.window.empty()) {
        a.windowName = state.window;
        a.window = model::displayWindow(state.window);
    }
    if (state.ambient != StudioState().ambient) a.ambient = float(state.ambient);
    a.lighting = state.lighting == "baked"     ? model::SurfaceSpec::Lighting::Baked
                 : state.lighting == "dynamic" ? model::SurfaceSpec::Lighting::Dynamic
                                               : model::SurfaceSpec::Lighting::Auto;
    a.bakeOptions.aoRays = state.bakeAo;
    a.bakeOptions.shadows = state.bakeShadows;
    if (state.shadows && state.lighting != "baked") a.shadows = true;
    if (!state.cut.empty()) a.cuts.push_back(model::SolidArgument(state.cut));  // relief:FILE read with the field
    a.clip = state.clip && !state.cut.empty();
    return a;
}

model::FigureSettings figureArgs(const StudioState& state) {
    model::FigureSettings f;
    f.enabled = state.figure;
    f.title = state.title;
    f.dpi = state.dpi;
    f.scaleBar = state.scaleBar;
    return f;
}

std::optional<io::FigureLayout> figureLayoutFor(const StudioState& state, int width, int height) {
    if (!state.figure) return std::nullopt;
    return model::figureLayout(figureArgs(state), width, height, model::figureHasColourBar(surfaceArgs(state)));
}

namespace {
/// The background a transparent export gives the CLI: the state's, else white, with alpha 0.
vec4 transparentBackground(const StudioState& state) { return vec4(vec3(state.background.value_or(vec4(1.0f))), 0.0f); }
}  // namespace

RenderSettings renderSettingsFor(const StudioState& state, bool transparent, const model::Surface& surface,
                                 const model::BackgroundSource& background) {
    model::RenderSpec spec = renderSpec(state, 1, 1);
    if (transparent) spec.background = transparentBackground(state);
    return model::renderSettings(surfaceArgs(state), surface, spec, background);
}

std::vector<std::string> inputArguments(const StudioState& state, std::string_view command) {
    std::vector<std::string> args{state.input};
    if (!state.variable.empty()) args.insert(args.end(), {"--var", state.variable});
    if (!state.time.empty()) args.insert(args.end(), {"--time", state.time});
    if (!state.series.empty()) args.insert(args.end(), {"--series", state.series});
    for (const auto& [key, text] : state.settings) {
        const model::Option* o = model::findOption(key);
        if (!o || !o->takenBy(command)) continue;
        args.push_back(std::string("--") + o->flag);
        if (o->kind != model::OptionKind::Flag) args.push_back(text);
    }
    return args;
}

std::vector<std::string> renderArguments(const StudioState& state, const Camera& camera, double iso,
                                         const std::string& output, int width, int height) {
    std::vector<std::string> args = inputArguments(state, "render");
    // An octree file fixes the iso value and the depth; a city model has no iso value.
    if (!model::isOctreeInput(state.input) && !io::isCityInput(state.input)) args.insert(args.end(), {"--iso", number(iso)});
    if (!model::isOctreeInput(state.input) && state.depth) args.insert(args.end(), {"--depth", std::to_string(*state.depth)});
    if (!state.cut.empty()) args.insert(args.end(), {"--cut", state.cut});
    if (state.clip && !state.cut.empty()) args.push_back("--clip");
    if (!state.lighting.empty()) args.insert(args.end(), {"--lighting", state.lighting});
    if (state.lighting == "baked") {
        args.insert(args.end(), {"--bake-ao", std::to_string(state.bakeAo)});
        if (!state.bakeShadows) args.insert(args.end(), {"--bake-shadows", "off"});
    } else if (state.shadows) {
        args.insert(args.end(), {"--shadows", "on"});
    }
    if (state.ambient != StudioState().ambient) args.insert(args.end(), {"--ambient", number(state.ambient)});
    args.insert(args.end(), {"--renderer", state.renderer, "--size", std::to_string(width) + "x" + std::to_string(height)});
    // The camera when the state has its own; else render's default framing, the studio's too
    // (model::frameCamera at the plot's size as the figure's text leaves it).
    if (state.cameraSet)
        args.insert(args.end(), {"--camera-pos", triple(camera.position.x, camera.position.y, camera.position.z),
                                 "--look-at", triple(camera.lookAt.x, camera.lookAt.y, camera.lookAt.z),
                                 "--up", triple(camera.up.x, camera.up.y, camera.up.z)});
    args.insert(args.end(), {"--fov", number(camera.fovYDegrees), "--light", triple(state.light.x, state.light.y, state.light.z)});
    // The coherence options, where they differ from the defaults and the renderer has them.
    const StudioState defaults;
    const RendererName chosen = resolveRendererName(state.renderer);
    const std::unique_ptr<Renderer> renderer = makeRenderer(chosen.renderer);
    const bool colourCoherence = state.colourCoherence && renderer->colourCoherence() && !chosen.colourCoherence;
    if (colourCoherence) args.emplace_back("--colour-coherence");
    if ((chosen.colourCoherence || colourCoherence) && state.colourTolerance != defaults.colourTolerance)
        args.insert(args.end(), {"--colour-tolerance", number(state.colourTolerance)});
    if ((chosen.colourCoherence || colourCoherence) && state.colourFillsBackground) args.emplace_back("--colour-fill-background");
    if (renderer->trajectoryCoherence() && state.branchUp != defaults.branchUp)
        args.insert(args.end(), {"--branch-up", std::to_string(state.branchUp)});
    if (renderer->missCoherence() && state.missCoherence != defaults.missCoherence)
        args.insert(args.end(), {"--miss-coherence", state.missCoherence ? "on" : "off"});
    if (colourGiven(state)) args.insert(args.end(), {"--colour", triple(state.colour.r, state.colour.g, state.colour.b)});
    if (!state.colormap.empty()) args.insert(args.end(), {"--colormap", state.colormap});
    if (!state.window.empty()) args.insert(args.end(), {"--window", state.window});
    if (state.background || state.transparent) {
        const vec4 b = state.transparent ? transparentBackground(state) : *state.background;
        args.insert(args.end(), {"--background", triple(b.r, b.g, b.b) + "," + number(b.a)});
    }
    if (state.figure) {
        args.insert(args.end(), {"--figure", "--dpi", std::to_string(state.dpi)});
        if (!state.title.empty()) args.insert(args.end(), {"--title", state.title});
        if (state.scaleBar) args.push_back("--scale-bar");
    }
    args.insert(args.end(), {"-o", output});
    return args;
}

}  // namespace octrace::studio
