#pragma once
// The studio's work off the GUI thread: reading an input and building its shell octree (with
// progress and Cancel), rendering the views' frames (newest request first), and exporting
// figures. Results come back as queued signals on the GUI thread; the window never waits.
#include "StudioState.h"
#include "octrace/model/Figure.h"
#include "octrace/model/Surface.h"
#include "Worker.h"

#include "octrace/build/ScalarField.h"
#include "octrace/octree/Octree.h"
#include "octrace/render/Frame.h"
#include "octrace/render/RenderStats.h"

#include <QImage>
#include <QObject>
#include <QString>

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

namespace octrace::studio {

/// What the window shows about the loaded input.
struct InputInfo {
    QString input, variable, units;
    QStringList variables;    ///< 3-D variables of a NetCDF file (empty for other formats)
    /// The variable read when none was asked for and the file has several (the first listed,
    /// where the CLI asks for --var): the window's state then names it; else empty.
    QString variableChosen;
    QStringList series;       ///< DICOM series as "N: description (modality, size)"
    int seriesRead = -1;      ///< the index in `series` of the series read (-1: not DICOM)
    bool octreeFile = false;  ///< a .oct input: no field, the iso value and depth are fixed
    double minimum = 0.0, maximum = 0.0;  ///< valid value range
    std::vector<double> histogram;        ///< counts of valid samples over [minimum, maximum]
    ValueWindow fileWindow;               ///< the display window stored in the file (DICOM), if any
    /// A patient volume without a stored window: its 1st to 99th percentile (model::quantileWindow),
    /// the slice panes' automatic window; computed with the read, off the GUI thread.
    ValueWindow percentileWindow;
    /// A geographic grid (NetCDF longitude, latitude, depth): the ocean controls apply. With the
    /// lon/lat mapping, the field read spans lonLat (LON0, LON1, LAT0, LAT1 in degrees); its
    /// levels span depths (metres, positive down) at verticalScale.
    bool geographic = false, polar = false;
    double lonLat[4] = {0.0, 0.0, 0.0, 0.0}, depths[2] = {0.0, 0.0};
    double verticalScale = 0.0;
    /// The steps of the input's time axis (io::readTimeAxis with the request read): a NetCDF
    /// variable's time steps (`time`), or the volumes of a 4-D series (`volume`, volumeSteps),
    /// each as the step slider names it (its date, or what tells the volume apart); fewer than
    /// two: nothing to step through.
    QStringList steps;
    bool volumeSteps = false;
};

/// One pane's rendered frame.
struct PaneFrame {
    QImage image;  ///< 8-bit sRGB as the PNG writer encodes it
    Frame frame;
    RenderStats stats;
    bool tracesRays = true;
};

/// Frames the window has shown, kept for the next render of the same size: a renderer reshapes a
/// frame of its size without allocating or clearing it (Frame::reshape), where a new frame costs
/// an allocation, its first-touch page faults and a clear on one thread inside the render's time
/// (10 ms for a 1280x800 frame in fresh memory, a fifth of an exact frame of CT bone).
/// Thread-safe.
class FramePool {
public:
    /// A kept frame of that size (its old content: the renderer writes or clears every pixel),
    /// or an empty frame.
    Frame take(int width, int height);
    /// Keeps `frame` (the newest first), at most kPerSize of a size and kKeepBytes in all.
    void give(Frame&& frame);
    static constexpr std::size_t kPerSize = 2;
    static constexpr std::uint64_t kKeepBytes = std::uint64_t(128) << 20;

private:
    std::mutex mutex_;
    std::vector<Frame> kept_;  // oldest first
};

/// What one frame request produced: one pane, or two for the split view with their comparison.
struct FrameResult {
    std::vector<PaneFrame> panes;
    bool preview = false;      ///< a coarse frame drawn while the camera moves
    double fullMs = 0.0;       ///< full traversal's time on the same frame (split view, exact frames)
    std::uint64_t mismatching = 0;  ///< pixels where the two panes differ (8-bit sRGB)
    QImage difference;         ///< |a - b| amplified, when asked for
    int level = -1;            ///< octree level drawn (preview), -1 = the voxels
    Camera camera;             ///< the camera of the frames (a preview's: half the size)
    std::uint64_t inputSerial = 0;  ///< the request's (LatencyMeter.h)
};

struct FrameRequest {
    std::vector<std::string> renderers;  ///< one or two
    Camera camera;
    RenderSettings settings;
    bool preview = false;
    bool difference = false;
    std::uint64_t inputSerial = 0;  ///< the latest input the frame shows (LatencyMeter.h), 0: none
};

class Engine : public QObject {
    Q_OBJECT
public:
    explicit Engine(QObject* parent = nullptr);
    ~Engine() override;

    /// Reads state.input (variable, time, series), then builds at state.iso (or the middle of
    /// the range) and state.depth. Cancels what is running.
    void open(const StudioState& state);
    /// Builds again from the loaded field with state's iso value, depth and colour options
    /// (they choose the display window).
    void rebuild(const StudioState& state);
    void cancel();
    bool building() const { return building_; }

    void requestFrame(const FrameRequest& request);
    /// Renders `state` at width x height off screen with its renderer and writes `path`
    /// (format by extension: PNG, EXR, TIFF); with state.figure the PNG figure around the plot
    /// (model::writeFigure, as render --figure).
    void exportFigure(const StudioState& state, const QString& path, int width, int height);

    const InputInfo& info() const { return info_; }
    /// The surface built, its octree and what the default look reads (its display window, its
    /// field's kind and grid, without the samples, which stay with the field read); null before
    /// the first build.
    std::shared_ptr<const model::Surface> surface() const { return surface_; }
    /// The surface's octree (part of surface()), or null.
    std::shared_ptr<const Octree> tree() const { return surface_ ? std::shared_ptr<const Octree>(surface_, &surface_->tree) : nullptr; }
    /// How the default camera sees the surface (model::sceneView of its field), as render does.
    model::SceneView view() const { return surface_ ? model::sceneView(surface_->field) : model::SceneView::Oblique; }
    double iso() const { return iso_; }
    int depth() const { return depth_; }
    /// The `depth` setting the surface was built with: unset when auto chose depth().
    std::optional<int> depthSetting() const { return depthAuto_ ? std::nullopt : std::optional<int>(depth_); }
    bool hasField() const { return bool(base_); }
    /// The field read, for the slice panes (SliceViews.h): the one the builds share their samples
    /// with (no second copy of them); null for inputs without a field (octree files, city models).
    std::shared_ptr<const ScalarField> field() const { return sliceField_; }
    /// The display window the build chose (model::Surface::window).
    ValueWindow window() const { return surface_ ? surface_->window : ValueWindow{}; }
    /// The render settings of `state` for the current surface (renderSettingsFor).
    RenderSettings settingsFor(const StudioState& state, bool transparent) const;
    /// What an export of `state` at width x height renders: the figure's layout with margins
    /// fitted to its text (as render --figure fits them; none without state.figure) and the
    /// camera at the size of the plot (or the whole image), cameraFor. Throws UsageError as
    /// figureLayoutFor; needs a surface.
    struct ExportView {
        std::optional<io::FigureLayout> layout;
        Camera camera;
    };
    ExportView exportView(const StudioState& state, int width, int height) const;

signals:
    /// fraction in [0,1], or < 0 when unknown.
    void progress(const QString& stage, double fraction);
    void inputLoaded();
    void surfaceBuilt();
    void frameReady(const octrace::studio::FrameResult& result);
    void exported(const QString& path, const QString& summary);
    void failed(const QString& message);
    void cancelled();

private:
    void startBuild(const StudioState& state);
    void setSurface(std::shared_ptr<const model::Surface> surface, model::FigureSubject subject, bool depthAuto);
    /// Runs `work` (a build job's body, on the worker) and hands a cancellation or an error
    /// back to the GUI thread (cancelled / failed) while `gen` is still the current build.
    void runBuildJob(unsigned gen, const std::function<void()>& work);
    /// Runs `then` on the GUI thread if `gen` is still the current build by then.
    void handBack(unsigned gen, std::function<void()> then);
    /// A job's hooks: progress of `stage` as the progress signal (one per percent at most, from
    /// any thread; to readProgress when `reading`, else to progress) and cancellation by `stop`.
    model::BuildHooks hooksFor(unsigned gen, const std::atomic<bool>& stop, const QString& stage, bool reading);

    InputInfo info_;
    std::shared_ptr<model::Surface> base_;  // holds the field read (its samples shared with each build)
    std::shared_ptr<const ScalarField> sliceField_;
    std::shared_ptr<const model::Surface> surface_;
    // settingsFor's contrasting background, for the surface and the colouring it was computed
    // for (a pass over every boundary voxel, asked on every camera move).
    struct BackgroundMemo {
        std::weak_ptr<const model::Surface> surface;
        RenderSettings colouring;
        vec4 background{0.0f};
    };
    mutable std::optional<BackgroundMemo> backgroundMemo_;
    double iso_ = 0.0;
    int depth_ = 0;
    bool depthAuto_ = false;
    model::FigureSubject subject_;  // what an exported figure says about the data
    bool building_ = false;
    unsigned generation_ = 0;  // the open/build whose results still count
    FramePool frames_;  // the shown frames, for the next renders
    // Last members: destroyed (joined) first, before what their jobs use.
    Worker exportWorker_, renderWorker_, buildWorker_;
};

/// The frame as 8-bit sRGB RGBA, quantized as the PNG writer does.
QImage toImage(const Frame& frame);
/// Writes `frame` to `path` by its extension (.png, .exr, .tif/.tiff); throws as io::writeImage.
void writeFigure(const Frame& frame, const std::string& path, bool alpha);

}  // namespace octrace::studio

Q_DECLARE_METATYPE(octrace::studio::FrameResult)
