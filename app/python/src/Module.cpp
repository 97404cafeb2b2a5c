// octrace._octrace: the pipeline library (app/model) for Python. The Python package
// (app/python/octrace) turns keyword arguments into settings texts by the options table and
// calls these; everything that reads, builds, renders or checks is the model's, as for the CLI.
// Work runs on a worker thread with the GIL released; the calling thread polls for Ctrl-C
// (KeyboardInterrupt cancels a build) and reports progress, so Python callbacks only ever run
// on the thread that called.
#include "Module.h"

#include "octrace/model/Figure.h"
#include "octrace/model/Input.h"
#include "octrace/model/Navigation.h"
#include "octrace/model/OptionTable.h"
#include "octrace/model/Render.h"
#include "octrace/model/Settings.h"
#include "octrace/model/Slice.h"
#include "octrace/model/Stats.h"
#include "octrace/model/Surface.h"

#include "octrace/io/Figure.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/io/OctreeFile.h"
#include "octrace/io/TimeAxis.h"
#include "octrace/io/VideoWriter.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/Renderer.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Parameter.h"
#include "octrace/util/Timer.h"

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/function.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <span>
#include <thread>
#include <vector>

namespace octrace::python {

// ---- Running work off the calling thread. ----

void interruptible(const std::function<void()>& work, std::atomic<bool>& cancel, const std::atomic<double>* fraction,
                   const nb::object& progress) {
    std::exception_ptr failure;
    std::mutex m;
    std::condition_variable finished;
    bool done = false, interrupted = false;
    double reported = -1.0;
    {
        nb::gil_scoped_release release;
        std::thread worker([&] {
            try {
                work();
            } catch (...) {
                failure = std::current_exception();
            }
            const std::lock_guard lock(m);
            done = true;
            finished.notify_one();
        });
        for (;;) {
            {
                std::unique_lock lock(m);
                if (finished.wait_for(lock, std::chrono::milliseconds(20), [&] { return done; })) break;
            }
            nb::gil_scoped_acquire acquire;
            if (!interrupted && PyErr_CheckSignals() != 0) {
                PyErr_Clear();
                interrupted = true;
                cancel = true;
            }
            if (fraction && !progress.is_none() && !interrupted && fraction->load() != reported) {
                reported = fraction->load();
                try {
                    progress(reported);
                } catch (...) {  // a failing callback stops the work like Ctrl-C, and its error is raised
                    cancel = true;
                    nb::gil_scoped_release again;
                    worker.join();
                    throw;
                }
            }
        }
        worker.join();
    }
    if (interrupted) {
        PyErr_SetNone(PyExc_KeyboardInterrupt);
        throw nb::python_error();
    }
    if (failure) std::rethrow_exception(failure);
    if (fraction && !progress.is_none() && reported < 1.0 && fraction->load() >= 1.0) progress(1.0);
}

// ---- Settings. ----

void applySettings(const Settings& settings, const model::SettingTargets& targets) {
    for (const auto& [key, text] : settings) {
        const model::Option* o = model::findOption(key);
        if (!o) throw UsageError("unknown setting " + param(key));
        if (!model::applySetting(*o, text, targets)) throw UsageError(param(key) + " is not a setting of this call");
    }
}

io::FieldRequest readerRequest(const Settings& settings) {
    model::SurfaceSpec spec;
    applySettings(settings, {.surface = &spec});
    io::FieldRequest req = spec.request;
    req.memoryBudget = model::memoryBudget(spec);
    return req;
}

Field makeField(ScalarField&& field, const std::string& input) {
    return Field{std::make_shared<const ScalarField>(std::move(field)), input, 0.0};
}

namespace {


// ---- Messages: the log's lines are kept until the call returns, then handed to Python. ----

std::mutex gLogMutex;
std::vector<std::pair<int, std::string>> gLogLines;

void collectLog(log::Level level, const std::string& text) {
    const std::lock_guard lock(gLogMutex);
    gLogLines.emplace_back(int(level), text);
}

/// The log's lines since the last call, oldest first ((level, text); level as log::Level).
std::vector<std::pair<int, std::string>> takeLog() {
    const std::lock_guard lock(gLogMutex);
    return std::exchange(gLogLines, {});
}

/// The table as Python sees it: one dict per option.
nb::list optionTable() {
    nb::list out;
    for (const model::Option* o : model::allOptions()) {
        nb::dict d;
        d["key"] = o->key;
        const char* kinds[] = {"flag", "integer", "number", "choice", "text"};
        d["kind"] = kinds[int(o->kind)];
        d["flag"] = *o->flag ? nb::cast(std::string("--") + o->flag) : nb::none();
        d["argument"] = o->argument;
        d["help"] = model::sayForPython(o->helpLine());
        d["default"] = model::sayForPython(o->defaultSaid());
        if (o->kind == model::OptionKind::Integer || o->kind == model::OptionKind::Number) {
            d["default_value"] = o->defaultValue;
            d["min"] = o->min;
            d["max"] = o->max;
            d["min_open"] = o->minOpen;
            d["max_open"] = o->maxOpen;
        }
        d["choices"] = o->choiceList();
        d["unit"] = o->unit;
        d["commands"] = o->commands;
        const char* parts[] = {"", "request", "surface", "render", "figure", "slice"};
        d["part"] = parts[int(model::settingPart(*o))];
        d["slice"] = model::sliceSetting(*o);
        d["shading"] = model::shadingSetting(*o);
        d["separator"] = model::valueSeparator(*o) ? nb::cast(std::string(1, model::valueSeparator(*o))) : nb::none();
        d["renderer_dependent"] = o->renderers != nullptr;
        d["needs"] = o->needs;
        out.append(d);
    }
    return out;
}

/// The warnings of `settings` that the renderer does not read (model::unusedWarning), as the
/// CLI gives them.
std::vector<std::string> unusedSettings(const std::vector<std::string>& keys, const std::string& renderer,
                                        const model::RenderSpec& spec) {
    const RendererName resolved = resolveRendererName(renderer);
    const std::unique_ptr<Renderer> r = makeRenderer(resolved.renderer);
    std::vector<std::string> out;
    for (const std::string& key : keys) {
        const model::Option* o = model::findOption(key);
        if (!o) continue;
        if (auto w = model::unusedWarning(*o, *r, renderer, [&](std::string_view k) {
                return k == model::opt::colourCoherence.key && (spec.coherence.colour || resolved.colourCoherence);
            }))
            out.push_back(model::sayForPython(*w));
    }
    return out;
}

// ---- Fields. ----


/// Reads `path` with the request's settings (var, region, time, series, ...): a field input.
Field readField(const std::string& path, const Settings& settings) {
    model::SurfaceSpec spec;
    spec.input = path;
    applySettings(settings, {.surface = &spec});
    auto s = std::make_shared<model::Surface>();
    std::atomic<bool> cancel{false};
    model::BuildHooks hooks;
    hooks.cancelled = [&] { return cancel.load(); };
    interruptible([&] { model::readSurfaceField(spec, *s, hooks); }, cancel);
    Field f;
    f.input = path;
    f.loadMs = s->loadMs;
    f.field = std::shared_ptr<const ScalarField>(s, &s->field);
    return f;
}

/// A field from C-contiguous float32 samples, axes (z, y, x) as NumPy holds a volume; NaN is
/// masked. `origin`, `spacing` in x, y, z order; `direction` row-major 3x3 whose columns are the
/// grid axes in world space.
Field arrayField(nb::ndarray<const float, nb::ndim<3>, nb::c_contig, nb::device::cpu> values, std::tuple<double, double, double> origin,
                 std::tuple<double, double, double> spacing, std::vector<double> direction, const std::string& name,
                 const std::string& units, bool patientLps) {
    auto f = std::make_shared<ScalarField>();
    f->name = name;
    f->units = units;
    f->source = name.empty() ? "array" : name;
    f->dims = ivec3(int(values.shape(2)), int(values.shape(1)), int(values.shape(0)));
    if (values.shape(0) > std::size_t(1 << 30) || values.shape(1) > std::size_t(1 << 30) || values.shape(2) > std::size_t(1 << 30))
        throw UsageError("the array is too large along an axis");
    f->origin = dvec3(std::get<0>(origin), std::get<1>(origin), std::get<2>(origin));
    f->spacing = dvec3(std::get<0>(spacing), std::get<1>(spacing), std::get<2>(spacing));
    if (direction.size() != 9) throw UsageError("`direction`: expected a 3x3 matrix, got " + std::to_string(direction.size()) + " numbers");
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) f->direction[c][r] = direction[std::size_t(r * 3 + c)];
    f->patientLps = patientLps;
    f->validateGeometry();
    const std::size_t n = f->sampleCount();
    const std::uint64_t budget = defaultMemoryBudget();
    checkMemoryBudget(f->source + ": " + std::to_string(n) + " samples", n * (sizeof(float) + 1), budget);
    bool masked = false;
    for (std::size_t i = 0; i < n && !masked; ++i) masked = !std::isfinite(values.data()[i]);
    if (!masked) {
        // Read in place: the field (and every surface built from it) keeps the array alive.
        f->values = SampleBuffer::borrow(values.data(), n, std::make_shared<decltype(values)>(values));
    } else {  // the samples are copied, NaN masked and zeroed: the caller's array is not changed
        f->values.assign(values.data(), values.data() + n);
        f->valid.assign(n, 1);
        for (std::size_t i = 0; i < n; ++i)
            if (!std::isfinite(f->values[i])) f->valid[i] = 0, f->values[i] = 0.0f;
    }
    f->validate();
    if (f->validCount() == 0) throw EmptyResultError(f->source + ": every sample is NaN or infinite");
    return Field{std::move(f), "", 0.0};
}

// ---- Surfaces. ----

/// A built surface: its spec (what built it) and the model's Surface (field, octree, reports).
struct Shell {
    model::SurfaceSpec spec;
    std::shared_ptr<model::Surface> surface;
    /// The octree's summaries, computed once for the first multi-resolution frame (frames may be
    /// rendered from several threads at once).
    std::shared_ptr<std::once_flag> summaries = std::make_shared<std::once_flag>();
    /// Built from a field without `surface`: the renderer, which decides between voxel and smooth
    /// (model::surfaceModeFor), is only known at each frame, so the corner values smooth frames
    /// need are not built with the octree but filled once, for the first smooth frame or save().
    bool cornersLater = false;
    std::shared_ptr<std::once_flag> corners = std::make_shared<std::once_flag>();
};

/// Fills the corner values of a surface built without them (Shell::cornersLater), once.
void fillCornersOnce(const Shell& sh) {
    if (!sh.cornersLater) return;
    std::call_once(*sh.corners, [&] {
        model::Surface& s = *sh.surface;
        if (s.tree.corners().empty() && !s.field.values.empty() && !s.spheres) fillCorners(s.tree, s.field, sh.spec.threads);
    });
}

/// Builds a surface from `field` (or, when null, from `input`: any input of the CLI, a city or an
/// octree file included) with the surface's settings; `progress(fraction)` as it goes.
Shell buildShell(const Field* field, const std::string& input, const Settings& settings, const nb::object& progress) {
    Shell sh;
    sh.spec.input = field ? (field->input.empty() ? field->field->source : field->input) : input;
    sh.spec.colours = true;
    applySettings(settings, {.surface = &sh.spec});
    sh.surface = std::make_shared<model::Surface>();
    // Without `surface`, no corner values yet (Shell::cornersLater): where later filling them from
    // the field gives what the build would (a plain shell of the field: no floor merged in, no cuts).
    model::SurfaceSpec build = sh.spec;
    sh.cornersLater = !sh.spec.surface && !sh.spec.floor && sh.spec.cuts.empty() && sh.spec.form == OctreeForm::Shell;
    if (sh.cornersLater) build.surface = SurfaceMode::Voxel;
    std::atomic<bool> cancel{false};
    std::atomic<double> fraction{0.0};
    model::BuildHooks hooks;
    hooks.progress = [&](double f) { fraction = f; };
    hooks.cancelled = [&] { return cancel.load(); };
    interruptible(
        [&] {
            if (!field) {
                *sh.surface = model::buildSurface(build, hooks);
                return;
            }
            // The field is shared: the surface takes a copy of its samples (the builder keeps
            // the field beside the octree, e.g. for colour_by and figures).
            sh.surface->field = field->field->copy();
            sh.surface->loadMs = field->loadMs;
            model::buildFromField(build, *sh.surface, hooks);
        },
        cancel, &fraction, progress);
    return sh;
}

Shell loadShell(const std::string& path, const Settings& settings) {
    Shell sh;
    sh.spec.input = path;
    sh.spec.colours = true;
    applySettings(settings, {.surface = &sh.spec});
    if (!model::isOctreeInput(path)) throw UsageError(path + ": not an octree file (.oct, as octrace build or Surface.save writes)");
    sh.surface = std::make_shared<model::Surface>();
    std::atomic<bool> cancel{false};
    interruptible([&] { *sh.surface = model::buildSurface(sh.spec); }, cancel);
    return sh;
}

void saveShell(const Shell& sh, const std::string& path, int level) {
    std::atomic<bool> cancel{false};
    interruptible(
        [&] {
            fillCornersOnce(sh);  // as `octrace build` writes them unless `surface` is voxel
            io::writeOctreeFile(path, sh.surface->tree, level);
        },
        cancel);
}

// ---- Frames. ----

/// Frames of images that Python let go, for the next renders of the same size. A frame is
/// 25 bytes a pixel (48 MB at 1600x1200), and a fresh one costs the kernel's first touch of
/// every page inside the renderer's timer; taken from here its pages are mapped, as the CLI's
/// --repeat renders into one frame. Holds at most two frames (a loop `img = shell.render()`
/// keeps one image alive while the next renders), and none beyond the memory budget's share.
class FramePool {
public:
    static FramePool& instance() {
        static FramePool pool;
        return pool;
    }
    /// A frame of that size from the pool, or an empty one (the renderer sizes it).
    Frame take(int width, int height) {
        const std::lock_guard lock(m_);
        for (auto it = frames_.begin(); it != frames_.end(); ++it)
            if (it->width == width && it->height == height) {
                Frame f = std::move(*it);
                frames_.erase(it);
                return f;
            }
        return {};
    }
    void give(Frame&& f) {
        if (f.width <= 0 || f.rgba.size() != f.pixel(0, f.height) || Frame::bytesFor(f.width, f.height) > defaultMemoryBudget() / 8) return;
        const std::lock_guard lock(m_);
        frames_.push_back(std::move(f));
        if (frames_.size() > 2) frames_.erase(frames_.begin());
    }

private:
    std::mutex m_;
    std::vector<Frame> frames_;
};

/// A rendered image: the frame (linear RGBA, depth, hits), its 8-bit sRGB pixels (what a PNG
/// holds), its stats, and its dpi when it is a figure. Its frame goes back to the FramePool.
struct Image {
    Image() = default;
    Image(Image&&) noexcept = default;
    Image& operator=(Image&&) noexcept = default;
    ~Image() { FramePool::instance().give(std::move(frame)); }

    Frame frame;
    model::Stats stats;
    int dpi = 0;
    /// height x width x 4, quantized when first asked for (under the GIL), so that a render
    /// whose pixels are not looked at costs no more than the CLI's.
    const std::vector<std::uint8_t>& rgba8() {
        if (rgba8_.empty()) rgba8_ = quantizeSrgb8(frame, 4);
        return rgba8_;
    }

private:
    std::vector<std::uint8_t> rgba8_;
};

Image renderShell(const Shell& sh, const Settings& surfaceSettings, const Settings& renderSettings) {
    model::SurfaceSpec spec = sh.spec;  // shading settings may be changed for this frame
    model::RenderSpec view;
    model::FigureSettings figure;
    applySettings(surfaceSettings, {.surface = &spec});
    applySettings(renderSettings, {.render = &view, .figure = &figure});
    const model::Surface& s = *sh.surface;
    const bool multires = model::checkRenderSpec(spec, view);
    std::optional<io::FigureLayout> layout;
    if (figure.enabled) {
        layout = model::figureLayout(figure, view.width, view.height, model::figureHasColourBar(spec));
        view.width = layout->plotW;
        view.height = layout->plotH;
    }
    const std::uint64_t budget = model::memoryBudget(spec);
    checkMemoryBudget(spec.input + ": rendering " + std::to_string(view.width) + "x" + std::to_string(view.height),
                      Frame::bytesFor(view.width, view.height) * (layout ? 2 : 1), budget);
    auto image = std::make_unique<Image>();
    std::atomic<bool> cancel{false};
    interruptible(
        [&] {
            if (multires) std::call_once(*sh.summaries, [&] { sh.surface->tree.computeSummaries(); });
            const Box3 bounds = s.tree.occupiedBounds();
            const model::SceneView sceneView = model::sceneView(s.field);
            const RenderSettings rs = model::renderSettings(spec, s, view);
            if (rs.surface == SurfaceMode::Smooth) fillCornersOnce(sh);
            if (layout) {
                // The plot takes the size the figure's text leaves.
                layout = model::fitFigureLayout(*layout, figure, model::figureSubject(s, spec.input), s.tree, rs, view, bounds, sceneView);
                view.width = layout->plotW;
                view.height = layout->plotH;
            }
            const Camera cam = model::frameCamera(view, bounds, sceneView);
            Frame frame = FramePool::instance().take(view.width, view.height);
            const RenderStats st = model::renderFrame(s.tree, cam, rs, view.renderer, frame);
            model::FrameRecord record = model::frameRecord(spec.input, s, cam, rs, st, view.renderer, bounds);
            record.figure = layout;
            record.multiResolution = multires;
            image->stats = model::frameStats(record);
            if (layout) {
                image->frame = io::composeFigure(frame, model::figureSpec(frame, figure, model::figureSubject(s, spec.input), s.tree, cam, rs), *layout);
                image->dpi = layout->dpi;
                FramePool::instance().give(std::move(frame));
            } else {
                image->frame = std::move(frame);
            }
        },
        cancel);
    return std::move(*image);
}

// ---- Slices. ----

/// The slice of `field` that `spec` asks for (model::renderSlice) as an Image with the CLI's
/// stats; on the calling thread (the caller runs it through interruptible).
Image sliceImage(const ScalarField& field, const model::SliceSpec& spec, double loadMs) {
    model::SliceResult r = model::renderSlice(field, spec);
    Image image;
    image.stats = model::sliceStats(field, r, spec.input, loadMs);
    image.dpi = r.dpi;
    image.frame = std::move(r.image);
    return image;
}

/// A slice of a field read already (a Volume) with the slice's settings.
Image sliceField(const Field& field, const Settings& settings) {
    model::SliceSpec spec;
    spec.input = field.input.empty() ? field.field->source : field.input;
    applySettings(settings, {.slice = &spec});
    return runInterruptible([&] { return sliceImage(*field.field, spec, field.loadMs); });
}

/// A slice of the file `path`, read as `octrace slice PATH` reads it (its request settings
/// among `settings`).
Image slicePath(const std::string& path, const Settings& settings) {
    model::SliceSpec spec;
    spec.input = path;
    applySettings(settings, {.slice = &spec});
    model::checkSliceSpec(spec);
    io::FieldRequest request = spec.request;
    request.memoryBudget = model::memoryBudget(spec);
    request.acceptPlanar = true;  // a 2-D field is drawn as a map
    return runInterruptible([&] {
        Timer t;
        const ScalarField field = model::loadField(path, request, int(model::opt::depth.defaultValue));
        return sliceImage(field, spec, t.ms());
    });
}

nb::dict cameraSettings(const Camera& c);

/// The camera a frame of `sh` with `renderSettings` has (framing the surface unless the
/// settings place it), moved by `move` ("" none, "orbit" yaw a and pitch b degrees, "pan" a, b
/// pixels of a view `viewHeight` high, "dolly" by the factor a): its settings as a dict of
/// camera_pos, look_at, up, fov, projection (and ortho_height), which render() takes back.
nb::dict moveCamera(const Shell& sh, const Settings& renderSettings, const std::string& move, double a, double b, int viewHeight) {
    model::RenderSpec view;
    applySettings(renderSettings, {.render = &view});
    Camera c = model::frameCamera(view, sh.surface->tree.occupiedBounds(), model::sceneView(sh.surface->field));
    if (move == "orbit") model::orbit(c, a, b);
    else if (move == "pan") model::pan(c, a, b, viewHeight);
    else if (move == "dolly") model::dolly(c, a);
    else if (!move.empty()) throw UsageError("unknown camera move '" + move + "' (orbit, pan, dolly)");
    return cameraSettings(c);
}

nb::dict cameraSettings(const Camera& c) {
    const auto triple = [](const dvec3& v) { return std::make_tuple(v.x, v.y, v.z); };
    nb::dict d;
    d["camera_pos"] = triple(c.position);
    d["look_at"] = triple(c.lookAt);
    d["up"] = triple(c.up);
    d["fov"] = c.fovYDegrees;
    d["projection"] = c.orthographic() ? "ortho" : "perspective";
    if (c.orthographic()) d["ortho_height"] = c.orthoHeight;
    return d;
}

/// The camera that frames `box` ((lo, hi) world corners) with `renderSettings` (size, fov,
/// projection, or a placed camera), turned `orbitDegrees` about its up axis through the look-at
/// point: an animation's fixed view of a grid that every frame shares.
nb::dict boxCamera(std::tuple<std::tuple<double, double, double>, std::tuple<double, double, double>> box, const Settings& renderSettings,
                   double orbitDegrees) {
    model::RenderSpec view;
    applySettings(renderSettings, {.render = &view});
    const auto& [lo, hi] = box;
    const Box3 b{dvec3(std::get<0>(lo), std::get<1>(lo), std::get<2>(lo)), dvec3(std::get<0>(hi), std::get<1>(hi), std::get<2>(hi))};
    Camera c = model::frameCamera(view, b);
    if (orbitDegrees != 0.0) model::orbit(c, orbitDegrees, 0.0);
    return cameraSettings(c);
}

/// A stats value as Python's.
nb::object statValue(const model::Stats::Value& v) {
    return std::visit(
        [](const auto& x) -> nb::object {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, std::nullptr_t>) return nb::none();
            else if constexpr (std::is_same_v<T, std::string>) return nb::cast(model::sayForPython(x));
            else return nb::cast(x);
        },
        v);
}

// ---- Errors: each of octrace's as a Python exception of the matching built-in kind. ----

PyObject* gUsageError = nullptr;   // ValueError: a setting or an argument is wrong
PyObject* gInputError = nullptr;   // ValueError: the input cannot give what is asked
PyObject* gFileError = nullptr;    // OSError: a file is missing, truncated or unreadable
PyObject* gLimitError = nullptr;   // MemoryError: more than the memory budget
PyObject* gOutputError = nullptr;  // OSError: an output cannot be written

void translate(const std::exception_ptr& p, void*) {
    try {
        std::rethrow_exception(p);
    } catch (const UsageError& e) {
        PyErr_SetString(gUsageError, model::sayForPython(e.what()).c_str());
    } catch (const FileError& e) {
        PyErr_SetString(gFileError, model::sayForPython(e.what()).c_str());
    } catch (const InputError& e) {
        PyErr_SetString(gInputError, model::sayForPython(e.what()).c_str());
    } catch (const LimitError& e) {
        PyErr_SetString(gLimitError, model::sayForPython(e.what()).c_str());
    } catch (const CancelledError&) {
        PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const OutputError& e) {
        PyErr_SetString(gOutputError, model::sayForPython(e.what()).c_str());
    }
}

PyObject* newError(nb::module_& m, const char* name, PyObject* base, const char* doc) {
    const std::string full = std::string("octrace.") + name;
    PyObject* type = PyErr_NewExceptionWithDoc(full.c_str(), doc, base, nullptr);
    if (!type) throw nb::python_error();
    m.attr(name) = nb::handle(type);
    return type;
}

}  // namespace
}  // namespace octrace::python

NB_MODULE(_octrace, m) {
    using namespace octrace;
    using namespace octrace::python;
    m.doc() = "octrace's pipeline library; use the package `octrace`, which checks keyword arguments by the options table";

    gUsageError = newError(m, "UsageError", PyExc_ValueError, "A setting or argument is wrong (the CLI's exit code 2).");
    gInputError = newError(m, "InputError", PyExc_ValueError, "The input cannot give what is asked (an unknown variable, an empty region).");
    gFileError = newError(m, "FileError", PyExc_OSError, "A file is missing, truncated, damaged or not in a format octrace reads.");
    gLimitError = newError(m, "LimitError", PyExc_MemoryError, "The work would need more memory than `max_memory` allows.");
    gOutputError = newError(m, "OutputError", PyExc_OSError, "An output cannot be written.");
    nb::register_exception_translator(translate);
    log::setSink(collectLog);

    m.def("options", &optionTable, "The options table: one dict per setting.");
    m.def("take_log", &takeLog, "The log's lines since the last call, as (level, text); level 0 debug .. 3 error.");
    m.def("renderer_names", [] { return rendererMenuNames(); });
    m.def("unused_settings", [](const std::vector<std::string>& keys, const std::string& renderer) {
        return unusedSettings(keys, renderer, model::RenderSpec{});
    });
    m.def("hardware_threads", [] { return hardwareThreads(); });
    m.def("describe", [](const std::string& path, const Settings& settings) {
        model::SurfaceSpec spec;
        applySettings(settings, {.surface = &spec});
        io::FieldRequest req = spec.request;
        req.memoryBudget = model::memoryBudget(spec);
        std::string text;
        std::atomic<bool> cancel{false};
        interruptible([&] { text = model::sayForPython(model::describe(path, req, spec.city)); }, cancel);
        return text;
    });
    m.def("is_field_input", [](const std::string& path) {
        return !model::isOctreeInput(path) && !io::isCityInput(path);
    });

    nb::class_<Field>(m, "Field")
        .def_prop_ro("name", [](const Field& f) { return f.field->name; })
        .def_prop_ro("units", [](const Field& f) { return f.field->units; })
        .def_prop_ro("standard_name", [](const Field& f) { return f.field->standardName; })
        .def_prop_ro("source", [](const Field& f) { return f.field->source; })
        .def_prop_ro("input", [](const Field& f) { return f.input; })
        .def_prop_ro("load_ms", [](const Field& f) { return f.loadMs; })
        .def_prop_ro("shape", [](const Field& f) {
            return std::make_tuple(f.field->dims.z, f.field->dims.y, f.field->dims.x);
        })
        .def_prop_ro("origin", [](const Field& f) { return std::make_tuple(f.field->origin.x, f.field->origin.y, f.field->origin.z); })
        .def_prop_ro("spacing", [](const Field& f) { return std::make_tuple(f.field->spacing.x, f.field->spacing.y, f.field->spacing.z); })
        .def_prop_ro("direction", [](const Field& f) {
            std::vector<double> d;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) d.push_back(f.field->direction[c][r]);
            return d;
        })
        .def_prop_ro("coords", [](const Field& f) {
            return std::make_tuple(f.field->coords[0], f.field->coords[1], f.field->coords[2]);
        })
        .def_prop_ro("patient_lps", [](const Field& f) { return f.field->patientLps; })
        .def_prop_ro("geographic", [](const Field& f) { return f.field->geographic.valid; })
        .def_prop_ro("notes", [](const Field& f) { return f.field->notes; })
        .def_prop_ro("bounds", [](const Field& f) {
            const Box3 b = f.field->worldBounds();
            return std::make_tuple(std::make_tuple(b.lo.x, b.lo.y, b.lo.z), std::make_tuple(b.hi.x, b.hi.y, b.hi.z));
        })
        .def_prop_ro("valid_range", [](const Field& f) { return f.field->validRange(); })
        .def_prop_ro("in_place", [](const Field& f) { return f.field->values.borrowed(); },
                     "True when the samples are read in place from the NumPy array given (no copy).")
        .def_prop_ro("values", [](const Field& f) {
            const ScalarField& s = *f.field;
            return nb::ndarray<nb::numpy, const float, nb::ndim<3>>(s.values.data(),
                {std::size_t(s.dims.z), std::size_t(s.dims.y), std::size_t(s.dims.x)}, nb::handle());
        }, nb::rv_policy::reference_internal, "The samples, axes (z, y, x), without a copy (read-only); masked samples hold 0.")
        .def_prop_ro("mask", [](const Field& f) -> nb::object {
            const ScalarField& s = *f.field;
            if (s.valid.empty()) return nb::none();
            return nb::cast(nb::ndarray<nb::numpy, const std::uint8_t, nb::ndim<3>>(s.valid.data(),
                {std::size_t(s.dims.z), std::size_t(s.dims.y), std::size_t(s.dims.x)}, nb::handle()), nb::rv_policy::reference);
        }, nb::keep_alive<0, 1>(), "1 where a sample is valid, axes (z, y, x); None when all are.");

    m.def("read_field", &readField, "path"_a, "settings"_a);
    m.def("cf_dates", &io::timeDates, "values"_a, "units"_a, "calendar"_a, "what"_a,
          "The dates of CF time coordinate values (as octrace info and animate captions say them); '' without CF time units.");
    m.def("height_range", [](const Field& f) { return model::gridHeightRange(*f.field); }, "field"_a,
          "The heights the field's grid spans, in the units colour_range takes for a surface coloured by height.");
    m.def("array_field", &arrayField, "values"_a, "origin"_a, "spacing"_a, "direction"_a, "name"_a, "units"_a, "patient_lps"_a);

    nb::class_<Shell>(m, "Shell")
        .def_prop_ro("input", [](const Shell& s) { return s.spec.input; })
        .def_prop_ro("iso", [](const Shell& s) { return s.surface->iso; })
        .def_prop_ro("depth", [](const Shell& s) { return s.surface->tree.depth; })
        .def_prop_ro("field_in_place", [](const Shell& s) { return s.surface->field.values.borrowed(); },
                     "True when the surface reads its Volume's NumPy array in place (no copy).")
        .def_prop_ro("boundary_voxels", [](const Shell& s) { return s.surface->tree.boundaryVoxels(); })
        .def_prop_ro("nodes", [](const Shell& s) { return s.surface->tree.nodes().size(); })
        .def_prop_ro("bytes", [](const Shell& s) { return s.surface->tree.bytes(); })
        .def_prop_ro("build_ms", [](const Shell& s) { return s.surface->report.buildMs; })
        .def_prop_ro("load_ms", [](const Shell& s) { return s.surface->loadMs; })
        .def_prop_ro("field_name", [](const Shell& s) { return s.surface->field.name.empty() ? s.surface->tree.fieldName() : s.surface->field.name; })
        .def_prop_ro("bounds", [](const Shell& s) {
            const Box3 b = s.surface->tree.occupiedBounds();
            return std::make_tuple(std::make_tuple(b.lo.x, b.lo.y, b.lo.z), std::make_tuple(b.hi.x, b.hi.y, b.hi.z));
        });
    m.def("build_shell", [](const Field* field, const std::string& input, const Settings& settings, nb::object progress) {
        return buildShell(field, input, settings, progress);
    }, "field"_a.none(), "input"_a, "settings"_a, "progress"_a.none());
    m.def("load_shell", &loadShell, "path"_a, "settings"_a);
    m.def("save_shell", &saveShell, "shell"_a, "path"_a, "level"_a);

    nb::class_<Image>(m, "Frame")
        .def_prop_ro("width", [](const Image& i) { return i.frame.width; })
        .def_prop_ro("height", [](const Image& i) { return i.frame.height; })
        .def_prop_ro("dpi", [](const Image& i) { return i.dpi; })
        .def_prop_ro("rgba", [](Image& i) {
            return nb::ndarray<nb::numpy, const std::uint8_t, nb::ndim<3>>(i.rgba8().data(),
                {std::size_t(i.frame.height), std::size_t(i.frame.width), 4}, nb::handle());
        }, nb::rv_policy::reference_internal)
        .def_prop_ro("depth", [](const Image& i) {
            return nb::ndarray<nb::numpy, const float, nb::ndim<2>>(i.frame.depth.data(),
                {std::size_t(i.frame.height), std::size_t(i.frame.width)}, nb::handle());
        }, nb::rv_policy::reference_internal)
        .def_prop_ro("stats", [](const Image& i) {
            nb::dict d;
            for (const auto& [k, v] : i.stats.entries()) d[k.c_str()] = statValue(v);
            return d;
        })
        .def("save", [](const Image& i, const std::string& path) {
            io::ImageWriteOptions options;
            options.dpi = i.dpi;
            std::atomic<bool> cancel{false};
            interruptible([&] { io::writeImage(i.frame, path, options); }, cancel);
        }, "path"_a);
    m.def("render", &renderShell, "shell"_a, "surface_settings"_a, "render_settings"_a);
    m.def("slice_field", &sliceField, "field"_a, "settings"_a);
    m.def("slice_path", &slicePath, "path"_a, "settings"_a);
    bindCfArrays(m);
    m.def("box_camera", &boxCamera, "box"_a, "render_settings"_a, "orbit_degrees"_a = 0.0);
    m.def("parse_number", [](const std::string& key, const std::string& text) {
        const model::Option* o = model::findOption(key);
        if (!o) throw UsageError("unknown setting " + param(key));
        return model::parseNumber(*o, text);
    }, "key"_a, "text"_a, "The number `text` with the options table's checks of setting `key`.");
    nb::class_<io::VideoWriter>(m, "VideoWriter", "An MP4 (H.264) written atomically when finished (io/VideoWriter.h).")
        .def(nb::init<std::string, int, int, int, int>(), "path"_a, "width"_a, "height"_a, "fps"_a, "quality"_a = 18)
        .def("add", [](io::VideoWriter& v, nb::ndarray<const std::uint8_t, nb::ndim<3>, nb::c_contig, nb::device::cpu> rgba) {
            if (rgba.shape(2) != 4) throw UsageError("a video frame is (H, W, 4) RGBA");
            const std::span<const std::uint8_t> pixels(rgba.data(), rgba.size());
            nb::gil_scoped_release release;
            v.add(pixels);
        }, "rgba"_a)
        .def("finish", [](io::VideoWriter& v) {
            nb::gil_scoped_release release;
            v.finish();
        })
        .def_prop_ro("codec", &io::VideoWriter::codec)
        .def_prop_ro("frames", &io::VideoWriter::frames);
    m.def("move_camera", &moveCamera, "shell"_a, "render_settings"_a, "move"_a, "a"_a = 0.0, "b"_a = 0.0, "view_height"_a = 1);
}
