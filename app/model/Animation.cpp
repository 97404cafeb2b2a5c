#include "octrace/model/Animation.h"

#include "octrace/model/Figure.h"
#include "octrace/model/Input.h"

#include "octrace/render/ImageCompare.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parameter.h"

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

namespace octrace::model {
namespace {

bool isIndex(const std::string& s) { return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos; }

std::size_t indexOf(const std::string& s, const std::string& text) {
    if (!isIndex(s) || s.size() > 12)
        throw UsageError(param("times") + ": expected all, I:J or DATE:DATE, got '" + text + "'");
    return std::size_t(std::stoull(s));
}

std::string stepsText(std::size_t n) { return std::to_string(n) + (n == 1 ? " step" : " steps"); }

}  // namespace

TimeSelection parseTimeSelection(const std::string& text) {
    TimeSelection s;
    if (text == "all") return s;
    static const std::regex dates(R"((\d{4}-\d{2}-\d{2}(?:[T ]\d{2}:\d{2}(?::\d{2}(?:\.\d+)?)?)?):(\d{4}-\d{2}-\d{2}.*))");
    std::smatch m;
    if (std::regex_match(text, m, dates)) {
        s.kind = TimeSelection::Kind::Dates;
        s.from = m[1];
        s.to = m[2];
        for (const std::string& d : {s.from, s.to}) {
            try {
                io::checkTimeText(d);
            } catch (const UsageError& e) {
                throw UsageError(param("times") + ": '" + d + "' is not a date YYYY-MM-DD[THH:MM[:SS]] (" + e.what() + ")");
            }
        }
        if (s.to.size() == s.from.size() && s.to < s.from)  // ISO texts of one width compare as their dates
            throw UsageError(param("times") + ": the range " + text + " ends before it starts");
        return s;
    }
    s.kind = TimeSelection::Kind::Indices;
    const std::size_t colon = text.find(':');
    s.first = indexOf(text.substr(0, colon), text);
    s.last = colon == std::string::npos ? s.first : indexOf(text.substr(colon + 1), text);
    if (s.last < s.first) throw UsageError(param("times") + ": the range " + text + " ends before it starts (I:J needs I <= J)");
    return s;
}

std::vector<std::size_t> selectSteps(const TimeSelection& selection, const io::TimeAxis& axis) {
    if (axis.empty())
        throw InputError(axis.path + ": the field has no time axis: an animation draws one frame per time step (octrace "
                                     "render draws a single surface)");
    std::vector<std::size_t> steps;
    switch (selection.kind) {
        case TimeSelection::Kind::All:
            for (std::size_t i = 0; i < axis.size; ++i) steps.push_back(i);
            break;
        case TimeSelection::Kind::Indices:
            if (selection.last >= axis.size)
                throw InputError(axis.path + ": time axis '" + axis.name + "' has " + stepsText(axis.size) + ", indices 0.." +
                                 std::to_string(axis.size - 1) + "; " + param("times") + " " + std::to_string(selection.first) +
                                 ":" + std::to_string(selection.last) + " goes beyond them");
            for (std::size_t i = selection.first; i <= selection.last; ++i) steps.push_back(i);
            break;
        case TimeSelection::Kind::Dates: {
            const double lo = axis.valueOf(selection.from), hi = axis.valueOf(selection.to);
            if (hi < lo) throw UsageError(param("times") + ": the range " + selection.from + ":" + selection.to + " ends before it starts");
            for (std::size_t i = 0; i < axis.values.size(); ++i)
                if (axis.values[i] >= lo && axis.values[i] <= hi) steps.push_back(i);
            if (steps.empty())
                throw InputError(axis.path + ": no step of time axis '" + axis.name + "' (" + axis.dates.front() + " .. " +
                                 axis.dates.back() + ", calendar " + axis.calendar + ") lies between " + selection.from +
                                 " and " + selection.to);
            break;
        }
    }
    return steps;
}

AnimationPlan planAnimation(const AnimationSpec& spec, const AnimationHooks& hooks) {
    AnimationPlan plan;
    plan.spec = spec;
    SurfaceSpec& surface = plan.spec.surface;
    if (!surface.request.time.empty())
        throw UsageError(param("time") + " chooses one step; an animation's steps are chosen by " + param("times"));
    if (surface.request.volume >= 0)
        throw UsageError(param("volume") + " chooses one volume; an animation's volumes are chosen by " + param("times"));
    const TimeSelection selection = parseTimeSelection(spec.times);
    if (isOctreeInput(surface.input) || isSphereInput(surface.input) || surface.input.rfind("analytic:", 0) == 0)
        throw InputError(surface.input + ": the field has no time axis: an animation draws one frame per time step");
    io::FieldRequest request = surface.request;
    request.memoryBudget = memoryBudget(surface);
    const io::TimeAxis axis = io::readTimeAxis(surface.input, request);
    if (axis.volumes && selection.kind == TimeSelection::Kind::Dates)
        throw InputError(surface.input + ": its " + std::to_string(axis.size) + " volumes have no dates: " + param("times") +
                         " takes all or I:J for them");
    const std::vector<std::size_t> steps = selectSteps(selection, axis);
    plan.timeAxis = axis.name;
    plan.calendar = axis.calendar;

    const double n = double(steps.size());
    for (std::size_t k = 0; k < steps.size(); ++k) {
        AnimationFrame f;
        f.step = steps[k];
        if (axis.volumes) {
            f.volume = int(f.step);
            const std::string& label = axis.labels[f.step];
            f.caption = "volume " + std::to_string(f.step) + (label.empty() ? "" : ": " + label);
        } else {
            f.time = std::to_string(f.step);
            f.date = axis.dates[f.step];
            f.caption = f.date.empty() ? "step " + f.time : f.date;
        }
        f.orbitDegrees = spec.orbitDegrees * double(k) / n;
        plan.frames.push_back(f);
    }

    // Every step shares the grid: its bounds, read at the first step, frame the camera.
    const double parts = 1.0 + ((!surface.colourBy.empty() && std::isnan(surface.colourMin)) ? n : 0.0);
    auto progress = [&](double done) {
        if (hooks.progress) hooks.progress(std::min(1.0, done / parts));
        if (hooks.cancelled && hooks.cancelled()) throw CancelledError("animation planning cancelled");
    };
    progress(0.0);
    request.time = plan.frames.front().time;
    request.volume = plan.frames.front().volume;
    const ScalarField grid = loadField(surface.input, request, readDepth(surface));
    plan.bounds = grid.worldBounds();
    plan.view = sceneView(grid);
    // `depth` auto: chosen once from the grid every step shares, so that the frames compare
    // (the build's memory check still refuses a step that would not fit).
    if (!surface.depth) {
        const DepthChoice c = depthForField(grid);
        surface.depth = c.depth;
        plan.notes.push_back(param("depth") + " auto: " + std::to_string(c.depth) + ", " + c.reason);
    }
    progress(1.0);
    // No `iso`: the first step's default (defaultIso) is every frame's, as render would choose
    // it for that step alone; each step's own would move the surface between frames for no
    // change of the data at the surface (the volumes of a series differ a little).
    if (!surface.iso && surface.isoPreset.empty()) {
        const auto [iso, why] = defaultIso(grid, surface.input);
        surface.iso = iso;
        surface.isoUnit.clear();
        plan.notes.push_back("every frame's surface at the iso value of the first: " + numberText(iso) + ", " + why + " (" +
                             param("iso") + " sets another)");
    }
    // The file's display window, as the first step gives it, greys every frame: each volume of
    // a DICOM series may carry its own, and the frames would not compare.
    if (surface.windowName.empty() && !surface.colourGiven && surface.colormap.empty() && surface.colourBy.empty() &&
        grid.window.valid()) {
        surface.window = grid.window;
        surface.windowName = numberText(grid.window.centre) + "," + numberText(grid.window.width);
        plan.notes.push_back("every frame greyed by the display window of the first (centre " + numberText(grid.window.centre) +
                             ", width " + numberText(grid.window.width) + "; " + param("window") + " sets another)");
    }

    // The colour range: given, or the union of colour_by's valid ranges over the steps.
    if (!std::isnan(surface.colourMin)) {
        plan.colourMin = surface.colourMin;
        plan.colourMax = surface.colourMax;
        plan.colourRangeSource = param("colour_range");
    } else if (!surface.colourBy.empty()) {
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        io::FieldRequest colour = request;
        colour.variable = surface.colourBy;
        for (std::size_t k = 0; k < plan.frames.size(); ++k) {
            colour.time = plan.frames[k].time;
            colour.volume = plan.frames[k].volume;
            const auto [vlo, vhi] = loadField(surface.input, colour, readDepth(surface)).validRange();
            lo = std::min(lo, vlo);
            hi = std::max(hi, vhi);
            progress(2.0 + double(k));
        }
        if (lo == hi) hi = lo + 1.0f;
        plan.colourMin = surface.colourMin = lo;
        plan.colourMax = surface.colourMax = hi;
        std::ostringstream s;
        s << param("colour_by") << " " << surface.colourBy << " over the " << stepsText(steps.size()) << ": [" << lo << ", " << hi << "]";
        plan.colourRangeSource = s.str();
        plan.notes.push_back("colour range " + plan.colourRangeSource + ", the same in every frame (the variable's values on "
                             "the grid read; " + param("colour_range") + " sets it)");
    } else if (!surface.colormap.empty() && surface.windowName.empty()) {
        const auto [lo, hi] = gridHeightRange(grid);
        plan.colourMin = surface.colourMin = float(lo);
        plan.colourMax = surface.colourMax = float(hi);
        std::ostringstream s;
        s << "height over the grid: [" << numberText(lo) << ", " << numberText(hi) << "]" << (grid.geographic.valid ? " m" : " (world z)");
        plan.colourRangeSource = s.str();
        plan.notes.push_back("coloured by " + plan.colourRangeSource + ", the same in every frame (" + param("colour_range") + " sets it)");
    }

    const RenderSpec& r = plan.spec.render;
    plan.width = r.width;
    plan.height = r.height;
    if (spec.figure.enabled) {
        plan.figureLayout = figureLayout(spec.figure, r.width, r.height, figureHasColourBar(surface));
        // The margins the first frame's text needs (fitFigureLayout), from its surface built
        // once more here; the other frames' text is laid out in the same margins.
        SurfaceSpec first = surface;
        first.request.time = plan.frames.front().time;
        first.request.volume = plan.frames.front().volume;
        const Surface built = buildSurface(first);
        const RenderSettings rs = renderSettings(first, built, r);
        FigureSettings settings = spec.figure;
        settings.caption = plan.frames.front().caption;
        plan.figureLayout = fitFigureLayout(*plan.figureLayout, settings, figureSubject(built, first.input), built.tree, rs, r, plan.bounds, plan.view);
        plan.spec.render.width = plan.figureLayout->plotW;
        plan.spec.render.height = plan.figureLayout->plotH;
        plan.width = plan.figureLayout->width;
        plan.height = plan.figureLayout->height;
    }
    surface.viewWidth = plan.spec.render.width;
    surface.viewHeight = plan.spec.render.height;
    surface.viewFov = plan.spec.render.fov;
    animationCamera(plan, 0);  // refuses a camera the spec cannot place before any frame is drawn
    return plan;
}

Camera animationCamera(const AnimationPlan& plan, std::size_t i) {
    if (i >= plan.frames.size())
        throw UsageError("animation frame " + std::to_string(i) + " of " + std::to_string(plan.frames.size()));
    Camera cam = frameCamera(plan.spec.render, plan.bounds, plan.view);
    const double angle = glm::radians(plan.frames[i].orbitDegrees);
    if (angle != 0.0) {
        const dvec3 axis = glm::normalize(cam.up);
        const dvec3 offset = cam.position - cam.lookAt;
        // Rodrigues' rotation of the eye's offset about the up axis through the look-at point.
        const dvec3 turned = offset * std::cos(angle) + glm::cross(axis, offset) * std::sin(angle) +
                             axis * glm::dot(axis, offset) * (1.0 - std::cos(angle));
        cam.position = cam.lookAt + turned;
        cam.validate();
    }
    return cam;
}

std::vector<std::uint8_t> AnimationImage::rgba8() const { return quantizeSrgb8(image, 4); }

AnimationImage renderAnimationFrame(const AnimationPlan& plan, std::size_t i, const BuildHooks& hooks) {
    const Camera cam = animationCamera(plan, i);
    const AnimationFrame& f = plan.frames[i];
    SurfaceSpec spec = plan.spec.surface;
    spec.request.time = f.time;
    spec.request.volume = f.volume;
    spec.colourMin = plan.colourMin;
    spec.colourMax = plan.colourMax;
    if (!spec.surface) spec.surface = surfaceModeFor(std::nullopt, plan.spec.render.renderer);
    const Surface surface = buildSurface(spec, hooks);
    const RenderSettings rs = renderSettings(spec, surface, plan.spec.render);
    AnimationImage out;
    Frame plot;
    out.stats = renderFrame(surface.tree, cam, rs, plan.spec.render.renderer, plot);
    if (!plan.figureLayout) {
        out.image = std::move(plot);
        return out;
    }
    FigureSettings settings = plan.spec.figure;
    settings.caption = f.caption;
    out.image = io::composeFigure(plot, figureSpec(plot, settings, figureSubject(surface, spec.input), surface.tree, cam, rs), *plan.figureLayout);
    return out;
}

}  // namespace octrace::model
