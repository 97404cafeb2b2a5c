#pragma once
// The studio's main window: input and surface controls on the left, one or two render panes
// (split view) in the middle, progress and Cancel in the status bar. Every control writes
// StudioState; the Engine does the work off the GUI thread.
#include "Engine.h"
#include "LatencyMeter.h"
#include "StudioState.h"

#include "octrace/render/Surfels.h"

#include <QMainWindow>
#include <QTimer>

#include <string_view>
#include <utility>
#include <vector>

class QAction;
class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;
class QLineEdit;
class QMenu;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class QSlider;
class QSpinBox;
class QStackedWidget;

namespace octrace::studio {

class HistogramView;
class SliceViews;
class OceanPanel;
class StepSlider;
class ViewInput;
class RenderView;
class SurfelView;

/// The export dialog's dpi when the figure's width goes from `fromWidth` to `toWidth` pixels:
/// in proportion, so that the text keeps its share of the figure (36..1200).
int scaledDpi(int dpi, int fromWidth, int toWidth);

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    /// Opens an input (any octrace INPUT, including analytic:NAME[:N]) with the current
    /// surface settings; the work runs in the background.
    void openInput(const QString& input);
    /// Starts exporting the current state to `path` at width x height (PNG, EXR, TIFF by the
    /// extension); Engine::exported or Engine::failed follows.
    void exportFigure(const QString& path, int width, int height, bool transparent);
    /// Saves the state as a session file (atomically); a failure shows a message.
    bool saveSessionTo(const QString& path);
    /// Opens a session file: its input is read with its settings and camera. A file that is
    /// missing or broken shows a message and keeps the current state.
    bool openSession(const QString& path);
    /// The figure options of the next exports (render --figure, --title, --dpi, --scale-bar);
    /// the export dialog sets them.
    void setFigure(bool figure, const QString& title, int dpi, bool scaleBar);
    /// The `octrace render` command line of the current state at width x height writing `output`.
    QStringList commandLine(const QString& output, int width, int height) const;

    const StudioState& state() const { return state_; }
    Engine& engine() { return engine_; }
    RenderView* view(int pane) const { return views_[pane]; }
    /// The OpenGL pane, made on first use.
    SurfelView* surfelView();
    /// The slice panes and the layout around the 3-D view (SliceViews.h).
    SliceViews* slices() const { return slices_; }
    /// The camera of pane views at their current size.
    Camera viewCamera() const;
    /// Input-to-paint latency of the camera moves in the main view (LatencyMeter.h).
    const LatencyMeter& latency() const { return latency_; }
    LatencyMeter& latency() { return latency_; }

signals:
    /// A frame (exact, not a preview) is on screen.
    void frameShown();
    /// The main view painted a frame that answered camera inputs; `ms`: the longest wait among them.
    void inputAnswered(double ms, bool preview);

protected:
    void dragEnterEvent(QDragEnterEvent*) override;
    void dropEvent(QDropEvent*) override;

private:
    void buildMenus();
    QWidget* buildControls();
    void showMessage(const QString& text, bool error = false);
    void addRecent(const QString& input);
    void updateRecentMenu();
    void onInputLoaded();
    void onSurfaceBuilt();
    void onFrame(const FrameResult& r);
    void setIsoControls(double iso);
    /// The depth controls after a build or a cancel: the engine's surface's depth, and whether
    /// auto chose it (the state's depth as the surface was built).
    void showBuiltDepth();
    void isoEdited(double iso);
    void scheduleBuild();
    void requestRender(bool preview);
    void cameraMoved(const Camera& c);
    void setStandardView(int axis, int sign);
    void setSplit(bool on);
    void chooseExport();
    void chooseOpen();
    /// Reads s's input with s's settings; the input fields, iso value and camera of s become
    /// the state's once it is read (a failed read changes nothing).
    void load(const StudioState& s);
    /// Sets every control from state_ without acting on the changes.
    void showState();
    void updateColourBar();
    /// After a change of the lighting: builds again when `rebuild` (the baked light depends on
    /// it), else renders.
    void lightingChanged(bool rebuild);
    /// Enables the coherence controls that the main pane's renderer, or the split view's
    /// second one, honours.
    void showCoherence();
    /// The controls of the bound settings marked renderingControl (StudioState.h: bindings()),
    /// each from its option's kind, label, range and tooltip, added to `form`.
    void addBoundControls(QFormLayout* form, QWidget* parent);
    /// What a bound control's change asks for (a frame or a build).
    void boundSettingChanged(const Binding& b);
    /// Whether the bound on/off setting `key` is on in the state.
    bool flagOn(std::string_view key) const;
    QWidget* buildCutControls(QWidget* parent);
    /// A solid of `kind` (box, sphere, halfspace) that cuts the part of `bounds` facing the default view.
    static QString defaultCut(const QString& kind, const Box3& bounds);
    /// Sets the cut-away solid (empty: none) after checking it, and builds again.
    void setCut(const QString& spec);
    void showCut();
    void connectNavigation(ViewInput* input);
    /// The main view painted the frame of inputs up to `serial`: their latencies, in the status bar.
    void framePainted(std::uint64_t serial);
    // The ocean controls and the step slider (MainWindowSteps.cpp).
    /// Makes the step slider (a row of the Input panel) and the ocean panel, and connects them.
    void buildStepAndOceanControls(QFormLayout* inputForm, QLayout* panel);
    /// After an input is read: the steps of its time axis, the ocean panel for a geographic field.
    void showStepsAndOcean();
    /// A text setting (StudioState::settings) edited: checked, then read, built or drawn again.
    void settingEdited(const QString& key, const QString& text);
    /// Reads step `index` of the time axis (`time`, or `volume` of a 4-D series).
    void stepChosen(int index);
    /// The step of the time axis that the state reads (0 when not given as an index).
    int currentStep() const;
    /// A step's read or build failed or was cancelled: Play stops, the slider shows the step on screen.
    void stepAbandoned();
    /// After a change of colour map or window: builds again when the display window changes,
    /// else renders.
    void colouringChanged();
    QSize paneSize() const;
    /// Whether the split view's right pane is the OpenGL view.
    bool openGlPane() const;
    /// Gives the OpenGL view the current surfels (extracted again when the surface or its
    /// colour changed) and camera.
    void updateSurfelView();
    /// Shows the slice panes' crosshair in the main 3-D view (four-up layout only).
    void showCrosshair();
    /// The state's layout, crosshair, slice positions and window from the slice panes.
    void keepSlices();

    StudioState state_;
    StudioState pending_;  // what load() is reading
    bool restoreSlices_ = false;  // a session's crosshair, positions and window wait for its input
    Engine engine_;
    RenderView* views_[2] = {nullptr, nullptr};
    QStackedWidget* secondPane_ = nullptr;
    SurfelView* surfelView_ = nullptr;
    SliceViews* slices_ = nullptr;
    std::shared_ptr<const std::vector<Surfel>> surfels_;
    std::shared_ptr<const Octree> surfelTree_;  // what surfels_ were extracted from
    RenderSettings surfelSettings_;
    HistogramView* histogram_ = nullptr;
    QLabel *inputLabel_ = nullptr, *rangeLabel_ = nullptr, *statusLabel_ = nullptr, *colourBar_ = nullptr;
    QComboBox *variableCombo_ = nullptr, *seriesCombo_ = nullptr, *rendererCombo_ = nullptr, *secondCombo_ = nullptr,
              *colormapCombo_ = nullptr, *windowCombo_ = nullptr, *isoPresetCombo_ = nullptr, *lightingCombo_ = nullptr,
              *cutCombo_ = nullptr;
    QLineEdit* cutEdit_ = nullptr;
    QCheckBox *clipCheck_ = nullptr, *bakeShadowsCheck_ = nullptr, *shadowsCheck_ = nullptr;
    QDoubleSpinBox* ambientSpin_ = nullptr;
    QSpinBox* bakeAoSpin_ = nullptr;
    // The controls made from bindings() (addBoundControls), named by the option's key.
    std::vector<std::pair<const Binding*, QWidget*>> boundControls_;
    QLineEdit* timeEdit_ = nullptr;
    StepSlider* stepSlider_ = nullptr;
    QLabel* stepLabel_ = nullptr;
    OceanPanel* oceanPanel_ = nullptr;
    bool stepPending_ = false;  // a step asked for by the slider is being read or built
    QSlider* isoSlider_ = nullptr;
    QDoubleSpinBox *isoSpin_ = nullptr, *fovSpin_ = nullptr, *lightSpin_[3] = {nullptr, nullptr, nullptr};
    QSpinBox* depthSpin_ = nullptr;
    QCheckBox* depthAutoCheck_ = nullptr;  ///< `depth` auto: the spin box shows what it chose
    QComboBox* surfaceCombo_ = nullptr;    ///< `surface`: auto (unset), voxel or smooth
    QProgressBar* progress_ = nullptr;
    QPushButton* cancelButton_ = nullptr;
    QPlainTextEdit* messages_ = nullptr;
    QAction *splitAction_ = nullptr, *differenceAction_ = nullptr;
    QMenu* recentMenu_ = nullptr;
    QTimer buildTimer_, exactTimer_;
    QString exportPath_ = QStringLiteral("figure.png");  // the export dialog's file: the last one exported
    bool updating_ = false;  // controls being set from the state: no feedback
    unsigned frameSerial_ = 0;
    LatencyMeter latency_;
    QLabel* latencyLabel_ = nullptr;
    bool shownPreview_ = false;  // the frame last given to the main view is a preview
};

}  // namespace octrace::studio
