#include "Engine.h"

#include "octrace/model/OptionTable.h"

#include "octrace/model/Input.h"
#include "octrace/model/Slice.h"
#include "octrace/model/Surface.h"

#include "octrace/build/OctreeBuilder.h"
#include "octrace/io/CityReader.h"
#include "octrace/io/FieldReader.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/io/TimeAxis.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/Renderer.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Timer.h"

#include <QMetaObject>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <utility>

namespace octrace::studio {
namespace {

constexpr int kHistogramBins = 128;

std::vector<double> histogramOf(const ScalarField& f, double lo, double hi) {
    std::vector<double> bins(kHistogramBins, 0.0);
    const double scale = hi > lo ? kHistogramBins / (hi - lo) : 0.0;
    for (std::size_t i = 0; i < f.values.size(); ++i) {
        if (!f.isValid(i) || !std::isfinite(f.values[i])) continue;
        const int b = std::clamp(int((double(f.values[i]) - lo) * scale), 0, kHistogramBins - 1);
        bins[std::size_t(b)] += 1.0;
    }
    return bins;
}

// Core and io name parameters by key (util/Parameter.h); the studio says its controls' labels.
QString errorText(const std::exception& e) { return QString::fromStdString(model::sayForStudio(e.what())); }

/// What the window shows of a geographic field read: the lon/lat box and depths it spans.
void describeGeographic(const ScalarField& f, InputInfo& info) {
    const ScalarField::Geographic& g = f.geographic;
    info.geographic = g.valid;
    if (!g.valid) return;
    info.polar = g.polar();
    info.verticalScale = g.verticalScale;
    const Box3 b = f.worldBounds();
    constexpr double kDegrees = 180.0 / 3.14159265358979323846;
    const double r = ScalarField::Geographic::kEarthRadiusKm;
    if (!g.polar()) {
        // The inverse of the contract's mapping (ScalarField.h).
        const double cosLat0 = std::cos(g.lat0 / kDegrees);
        info.lonLat[0] = g.lon0 + b.lo.x / (r * cosLat0) * kDegrees;
        info.lonLat[1] = g.lon0 + b.hi.x / (r * cosLat0) * kDegrees;
        info.lonLat[2] = g.lat0 + b.lo.y / r * kDegrees;
        info.lonLat[3] = g.lat0 + b.hi.y / r * kDegrees;
    }
    info.depths[0] = -b.hi.z / g.verticalScale * 1000.0;
    info.depths[1] = -b.lo.z / g.verticalScale * 1000.0;
}

/// The steps of the input's time axis, named for the step slider.
void describeSteps(const std::string& input, const io::FieldRequest& request, InputInfo& info) {
    const io::TimeAxis axis = io::readTimeAxis(input, request);
    info.volumeSteps = axis.volumes;
    for (std::size_t i = 0; i < axis.size; ++i) {
        // "volume 2 of 4": the index the box and the CLI take (from 0), and how many there are.
        QString name = (axis.volumes ? QStringLiteral("volume %1 of %2") : QStringLiteral("step %1 of %2")).arg(i).arg(axis.size);
        if (axis.volumes && i < axis.labels.size() && !axis.labels[i].empty())
            name += QStringLiteral(": ") + QString::fromStdString(axis.labels[i]);
        else if (axis.dated() && i < axis.dates.size())
            name += QStringLiteral(": ") + QString::fromStdString(axis.dates[i]);
        info.steps << name;
    }
}

/// Moves `field`'s samples to a shared owner (SampleBuffer.h), so that copies share them: the
/// builds read them in place instead of a second copy of the field.
void shareSamples(ScalarField& field) {
    if (field.values.borrowed()) return;
    auto owner = std::make_shared<const std::vector<float>>(std::move(field.values.vector()));
    field.values = SampleBuffer::borrow(owner->data(), owner->size(), owner);
}

/// The preview level while the camera moves: two levels above the voxels, at least 1.
int previewLevel(int depth) { return std::max(1, depth - 2); }

}  // namespace

QImage toImage(const Frame& frame) {
    // Qt's 32-bit layout, written in place on all cores; an opaque frame is marked RGB32, which
    // Qt paints by copying rows (an image with alpha is blended pixel by pixel).
    QImage img(frame.width, frame.height, QImage::Format_ARGB32);
    if (img.isNull()) return img;
    if (packSrgb8Rows(frame, img.bits(), std::size_t(img.bytesPerLine()), 0)) img.reinterpretAsFormat(QImage::Format_RGB32);
    return img;
}

void writeFigure(const Frame& frame, const std::string& path, bool alpha) {
    io::ImageWriteOptions o;
    o.alpha = alpha;
    io::writeImage(frame, path, o);
}

Frame FramePool::take(int width, int height) {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = kept_.rbegin(); it != kept_.rend(); ++it)
        if (it->width == width && it->height == height) {
            Frame f = std::move(*it);
            kept_.erase(std::next(it).base());
            return f;
        }
    return Frame();
}

void FramePool::give(Frame&& frame) {
    auto bytes = [](const Frame& f) { return Frame::bytesFor(f.width, f.height); };
    if (frame.width <= 0 || frame.height <= 0 || bytes(frame) > kKeepBytes) return;  // not kept
    const std::lock_guard<std::mutex> lock(mutex_);
    // The oldest of its size beyond kPerSize go, then the oldest of any size beyond kKeepBytes.
    std::size_t same = 0;
    for (const Frame& f : kept_) same += f.width == frame.width && f.height == frame.height;
    for (auto it = kept_.begin(); same >= kPerSize && it != kept_.end();)
        if (it->width == frame.width && it->height == frame.height) {
            it = kept_.erase(it);
            --same;
        } else {
            ++it;
        }
    kept_.push_back(std::move(frame));
    std::uint64_t total = 0;
    for (const Frame& f : kept_) total += bytes(f);
    while (total > kKeepBytes) {  // the newest alone fits
        total -= bytes(kept_.front());
        kept_.erase(kept_.begin());
    }
}

Engine::Engine(QObject* parent) : QObject(parent) { qRegisterMetaType<FrameResult>(); }

Engine::~Engine() {
    buildWorker_.cancel();
    renderWorker_.cancel();
    exportWorker_.cancel();
}

void Engine::cancel() {
    buildWorker_.cancel();
    if (!building_) return;
    // Whether the job was still waiting (dropped) or running (it stops at its next check), its
    // results no longer count.
    ++generation_;
    building_ = false;
    emit cancelled();
}

namespace {
/// Inputs whose surface is not built from a field here: an octree file (fixed iso and depth)
/// and a city model (voxelized whole).
bool fixedSurface(const std::string& input) { return model::isOctreeInput(input) || io::isCityInput(input); }
}  // namespace

void Engine::open(const StudioState& state) {
    const unsigned gen = ++generation_;
    building_ = true;
    emit progress(tr("Reading %1").arg(QString::fromStdString(state.input)), -1.0);
    buildWorker_.post([this, state, gen](const std::atomic<bool>& stop) {
        runBuildJob(gen, [&] {
            InputInfo info;
            info.input = QString::fromStdString(state.input);
            model::SurfaceSpec a = surfaceArgs(state);
            if (fixedSurface(state.input)) {
                // As `octrace render` reads them (no field options, no iso value).
                a.request = {};
                a.iso.reset();
                auto surface = std::make_shared<model::Surface>(model::buildSurface(a));
                surface->tree.computeSummaries();
                info.octreeFile = true;
                info.variable = QString::fromStdString(surface->tree.fieldName());
                info.units = QString::fromStdString(surface->tree.fieldUnits());
                info.minimum = info.maximum = surface->iso;
                handBack(gen, [this, info, surface = std::shared_ptr<const model::Surface>(surface),
                               subject = model::figureSubject(*surface, state.input),
                               depthAuto = !state.depth && !model::isOctreeInput(state.input)] {
                    info_ = info;
                    base_.reset();
                    sliceField_.reset();
                    setSurface(surface, subject, depthAuto);
                    emit inputLoaded();
                    emit surfaceBuilt();
                });
                return;
            }
            if (state.input.rfind("analytic:", 0) != 0) {
                // The headers scanned for the Series box: Cancel stops this scan too (its progress
                // is not shown: the read scans them again, with progress, below).
                io::InputChoices choices = io::listInputChoices(state.input, {{}, [&stop] { return stop.load(); }});
                for (const auto& v : choices.variables) info.variables << QString::fromStdString(v);
                // Several variables and none chosen: the first, which the Variable box then shows.
                if (a.request.variable.empty() && choices.variables.size() > 1) {
                    a.request.variable = choices.variables.front();
                    info.variableChosen = QString::fromStdString(a.request.variable);
                }
                int n = 0;
                for (const auto& s : choices.series)
                    info.series << QStringLiteral("%1: %2 (%3, %4x%5x%6%7)")
                                       .arg(++n)
                                       .arg(QString::fromStdString(s.description.empty() ? s.uid : s.description))
                                       .arg(QString::fromStdString(s.modality))
                                       .arg(s.columns)
                                       .arg(s.rows)
                                       .arg(s.slices)
                                       .arg(s.volumes > 1 ? QStringLiteral(", %1 volumes").arg(s.volumes) : QString());
                // The series the reader takes, for the Series box to show (the default is
                // the largest, not the first listed).
                if (!choices.series.empty())
                    info.seriesRead = int(io::DicomReader::chooseSeries(choices.series, a.request.series, state.input));
            }
            auto base = std::make_shared<model::Surface>();
            model::readSurfaceField(a, *base, hooksFor(gen, stop, tr("Reading %1").arg(QString::fromStdString(state.input)), true));
            if (stop) throw CancelledError("cancelled");
            if (state.input.rfind("analytic:", 0) != 0) describeSteps(state.input, a.request, info);
            describeGeographic(base->field, info);
            auto [lo, hi] = base->field.validRange();
            info.variable = QString::fromStdString(base->field.name);
            info.units = QString::fromStdString(base->field.units);
            info.minimum = lo;
            info.maximum = hi;
            info.histogram = histogramOf(base->field, lo, hi);
            info.fileWindow = base->field.window;
            if (base->field.patientLps && !base->field.window.valid()) info.percentileWindow = model::quantileWindow(base->field, 0.01, 0.99);
            // One field: the slice panes read the one the builds copy their samples from.
            shareSamples(base->field);
            std::shared_ptr<const ScalarField> sliceField(base, &base->field);
            if (stop) throw CancelledError("cancelled");
            StudioState read = state;
            read.variable = a.request.variable;
            handBack(gen, [this, info, base, sliceField, read] {
                info_ = info;
                base_ = base;
                sliceField_ = sliceField;
                surface_.reset();
                emit inputLoaded();
                startBuild(read);
            });
        });
    });
}

void Engine::handBack(unsigned gen, std::function<void()> then) {
    QMetaObject::invokeMethod(this, [this, gen, then = std::move(then)] {
        if (gen == generation_) then();
    }, Qt::QueuedConnection);
}

model::BuildHooks Engine::hooksFor(unsigned gen, const std::atomic<bool>& stop, const QString& stage, bool reading) {
    model::BuildHooks hooks;
    auto shown = std::make_shared<std::atomic<int>>(-1);  // percent last sent
    auto report = [this, shown, gen, stage](double f) {
        const int pc = int(f * 100.0);
        if (shown->exchange(pc) == pc) return;
        handBack(gen, [this, stage, f] { emit progress(stage, f); });
    };
    (reading ? hooks.readProgress : hooks.progress) = report;
    hooks.cancelled = [&stop] { return stop.load(); };
    return hooks;
}

void Engine::runBuildJob(unsigned gen, const std::function<void()>& work) {
    try {
        work();
    } catch (const CancelledError&) {
        handBack(gen, [this] {
            building_ = false;
            emit cancelled();
        });
    } catch (const std::exception& e) {
        handBack(gen, [this, msg = errorText(e)] {
            building_ = false;
            emit failed(msg);
        });
    }
}

void Engine::rebuild(const StudioState& state) {
    if (!base_) return;
    ++generation_;
    startBuild(state);
}

void Engine::setSurface(std::shared_ptr<const model::Surface> surface, model::FigureSubject subject, bool depthAuto) {
    surface_ = std::move(surface);
    iso_ = subject.iso;
    subject_ = std::move(subject);
    depth_ = surface_->tree.depth;
    depthAuto_ = depthAuto;
    building_ = false;
}

void Engine::startBuild(const StudioState& state) {
    const unsigned gen = generation_;
    building_ = true;
    emit progress(tr("Building the octree"), 0.0);
    buildWorker_.post([this, base = base_, state, gen](const std::atomic<bool>& stop) {
        // The build's field shares the samples of the one read (which the slice panes read on
        // the GUI thread meanwhile: neither writes it); only its small members and its validity
        // mask (a byte a sample, less than the read needed) are copied for the build's time.
        auto surface = std::make_shared<model::Surface>();
        surface->field = std::as_const(base->field).copy();
        surface->spheres = base->spheres;
        runBuildJob(gen, [&] {
            model::buildFromField(surfaceArgs(state), *surface, hooksFor(gen, stop, tr("Building the octree"), false));
            surface->tree.computeSummaries();
            // The subject now. The surface kept has the field's grid and kind without its
            // samples and mask (`base` keeps them), which is what its look and framing read
            // (model::renderSettings, model::sceneView), as render reads them of its field.
            model::FigureSubject subject = model::figureSubject(*surface, state.input);
            surface->field.values = SampleBuffer();
            surface->field.valid.clear();
            handBack(gen, [this, surface = std::shared_ptr<const model::Surface>(surface), subject = std::move(subject),
                           depthAuto = !state.depth] {
                setSurface(surface, subject, depthAuto);
                emit surfaceBuilt();
            });
        });
    });
}

namespace {
Engine::ExportView exportViewOf(const StudioState& state, const model::Surface& surface, const model::FigureSubject& subject,
                                const RenderSettings& rs, int width, int height) {
    Engine::ExportView out;
    out.layout = figureLayoutFor(state, width, height);
    const Box3 bounds = surface.tree.occupiedBounds();
    const model::SceneView view = model::sceneView(surface.field);
    if (out.layout)
        out.layout = model::fitFigureLayout(*out.layout, figureArgs(state), subject, surface.tree, rs, renderSpec(state, width, height),
                                            bounds, view);
    out.camera = out.layout ? cameraFor(state, bounds, view, out.layout->plotW, out.layout->plotH) : cameraFor(state, bounds, view, width, height);
    return out;
}
}  // namespace

Engine::ExportView Engine::exportView(const StudioState& state, int width, int height) const {
    if (!surface_) throw UsageError("nothing to export: open an input first");
    return exportViewOf(state, *surface_, subject_, settingsFor(state, state.transparent), width, height);
}

RenderSettings Engine::settingsFor(const StudioState& state, bool transparent) const {
    if (surface_) {
        // GUI thread only (like every caller of settingsFor), so the memo needs no lock.
        const auto memo = [this](const Octree& tree, const RenderSettings& rs) {
            const auto& m = backgroundMemo_;
            const bool sameSurface = m && !m->surface.owner_before(surface_) && !surface_.owner_before(m->surface) && !m->surface.expired();
            if (sameSurface && model::sameColouring(m->colouring, rs)) return m->background;
            backgroundMemo_ = BackgroundMemo{surface_, rs, model::contrastingBackground(tree, rs)};
            return backgroundMemo_->background;
        };
        return renderSettingsFor(state, transparent, *surface_, memo);
    }
    return renderSettingsFor(state, transparent, model::Surface());
}

void Engine::requestFrame(const FrameRequest& request) {
    auto tree = this->tree();
    if (!tree || request.renderers.empty()) return;
    // A preview does not cancel the frame being rendered: a render runs to its end whatever the
    // flag says (it is read between panes), so cancelling only threw the finished frame away.
    // With the mouse moving faster than previews render (a 60 Hz mouse, previews of 20 ms and
    // more), every preview was thrown away and nothing was painted until the button was released
    // (bench/studio_latency.py, before this change: no preview painted during a 60 Hz orbit of
    // CT bone at depth 9). The waiting request is still replaced by the newest.
    renderWorker_.post([this, tree, request](const std::atomic<bool>& stop) {
        try {
            FrameResult out;
            out.preview = request.preview;
            out.inputSerial = request.inputSerial;
            RenderSettings rs = request.settings;
            Camera cam = request.camera;
            if (request.preview) {
                // A smaller image of a coarser level first: the exact frame follows when the
                // camera stops.
                cam.width = std::max(1, cam.width / 2);
                cam.height = std::max(1, cam.height / 2);
                out.level = previewLevel(tree->depth);
            }
            out.camera = cam;
            for (const auto& name : request.renderers) {
                if (stop) return;
                const RendererName resolved = resolveRendererName(name);
                auto r = makeRenderer(resolved.renderer);
                RenderSettings s = rs;
                resolved.applyTo(s);
                if (request.preview && r->multiResolution()) s.detail.level = out.level;
                // A newer exact frame stops this one (the tile renderer between its groups of
                // tiles): a preview still drawing when the button is released no longer delays
                // the exact frame by its own length.
                s.cancel = &stop;
                PaneFrame p;
                p.frame = frames_.take(cam.width, cam.height);
                p.stats = r->render(*tree, cam, s, p.frame);
                if (stop) return;
                p.tracesRays = r->tracesRays();
                p.image = toImage(p.frame);
                out.panes.push_back(std::move(p));
            }
            if (out.panes.size() == 2 && !request.preview) {
                const ImageDifference d = compareImages(out.panes[0].frame, out.panes[1].frame);
                out.mismatching = d.differingPixels;
                // Speed-up over full traversal: full's own time on this frame.
                double full = -1.0;
                for (const auto& p : out.panes)
                    if (p.stats.renderer == "full") full = p.stats.renderMs;
                if (full < 0.0 && !stop) {
                    Frame f;
                    full = makeRenderer("full")->render(*tree, cam, rs, f).renderMs;
                }
                out.fullMs = full;
                if (request.difference) {
                    const Frame& a = out.panes[0].frame;
                    const Frame& b = out.panes[1].frame;
                    QImage diff(a.width, a.height, QImage::Format_RGB32);
                    for (int y = 0; y < a.height; ++y)
                        for (int x = 0; x < a.width; ++x) {
                            const vec4 ca = a.rgba[a.pixel(x, y)], cb = b.rgba[b.pixel(x, y)];
                            auto ch = [](float u, float v) {
                                return std::min(255, 4 * std::abs(int(linearToSrgb8(u)) - int(linearToSrgb8(v))));
                            };
                            diff.setPixel(x, y, qRgb(ch(ca.r, cb.r), ch(ca.g, cb.g), ch(ca.b, cb.b)));
                        }
                    out.difference = diff;
                }
            }
            if (stop) return;
            QMetaObject::invokeMethod(
                this,
                [this, out = std::move(out)]() mutable {
                    emit frameReady(out);
                    for (PaneFrame& p : out.panes) frames_.give(std::move(p.frame));  // shown: the next render's
                },
                Qt::QueuedConnection);
        } catch (const std::exception& e) {
            QMetaObject::invokeMethod(this, [this, msg = errorText(e)] { emit failed(msg); }, Qt::QueuedConnection);
        }
    }, /*cancelRunning=*/!request.preview);
}

void Engine::exportFigure(const StudioState& state, const QString& path, int width, int height) {
    auto surface = surface_;
    if (!surface) {
        emit failed(tr("Nothing to export: open an input first"));
        return;
    }
    emit progress(tr("Exporting %1x%2").arg(width).arg(height), -1.0);
    exportWorker_.post([this, surface, state, path, width, height, subject = subject_](const std::atomic<bool>&) {
        const Octree* tree = &surface->tree;
        try {
            if (width < 1 || height < 1 || width > kMaxExportSide || height > kMaxExportSide)
                throw UsageError("export size " + std::to_string(width) + "x" + std::to_string(height) +
                                 ": each side must be 1.." + std::to_string(kMaxExportSide) + " pixels");
            if (state.figure) model::checkFigureFormat(path.toStdString());
            // The figure's layout first: the plot is the part of the image that is rendered.
            const std::optional<io::FigureLayout> first = figureLayoutFor(state, width, height);
            const std::uint64_t bytes = Frame::bytesFor(width, height) * (first ? 2 : 1) + std::uint64_t(width) * std::uint64_t(height) * 24;
            checkMemoryBudget("exporting " + std::to_string(width) + "x" + std::to_string(height), bytes,
                              defaultMemoryBudget());
            const RenderSettings rs = renderSettingsFor(state, state.transparent, *surface);
            // The margins the figure's text needs, as render --figure fits them.
            const ExportView v = exportViewOf(state, *surface, subject, rs, width, height);
            const std::optional<io::FigureLayout>& layout = v.layout;
            Camera cam = v.camera;
            cam.validate();
            Frame frame;
            const RenderStats st = model::renderFrame(*tree, cam, rs, state.renderer, frame);
            if (layout) model::writeFigure(frame, figureArgs(state), *layout, subject, *tree, cam, rs, path.toStdString());
            else writeFigure(frame, path.toStdString(), state.transparent);
            const QString summary = tr("%1: %2x%3, %4, %5 ms")
                                        .arg(path)
                                        .arg(width)
                                        .arg(height)
                                        .arg(QString::fromStdString(st.renderer))
                                        .arg(st.renderMs, 0, 'f', 1);
            QMetaObject::invokeMethod(this, [this, path, summary] { emit exported(path, summary); }, Qt::QueuedConnection);
        } catch (const std::exception& e) {
            QMetaObject::invokeMethod(this, [this, msg = errorText(e)] { emit failed(msg); }, Qt::QueuedConnection);
        }
    }, false);
}

}  // namespace octrace::studio
