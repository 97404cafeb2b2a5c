#pragma once
// The studio's radiology layout: axial, coronal and sagittal slice panes (SlicePane.h) beside
// the 3-D view, as 3D Slicer's four-up layout (axial upper left, 3-D upper right, sagittal
// lower left, coronal lower right), or the 3-D view alone. The panes share one crosshair, a
// sample (i, j, k) of the field read, which the 3-D view shows and a click on its surface
// moves; the window comes from the CT presets (CtPresets.h), a drag, or automatically (the
// file's window, else the volume's 1st to 99th percentile: MR has no presets). The probe line
// under the panes says the value and the patient position (LPS and RAS) under the pointer.
// Slices are drawn on the GUI thread by model::renderSlice, the code of `octrace slice`: a
// pane's image is pixel for pixel what `commandLine` makes the CLI write.
#include "SlicePane.h"

#include "octrace/build/ScalarField.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Frame.h"

#include <QWidget>

#include <array>
#include <functional>
#include <memory>
#include <optional>

class QAction;
class QActionGroup;
class QComboBox;
class QDoubleSpinBox;
class QGridLayout;
class QLabel;
class QToolButton;

namespace octrace::studio {

class Engine;

class SliceViews : public QWidget {
    Q_OBJECT
public:
    /// Lays out `threeD` (the 3-D view, reparented here) with the three panes; follows
    /// `engine`'s inputs (the field it read) and frames (what a click on the surface picks).
    SliceViews(QWidget* threeD, Engine& engine, QWidget* parent = nullptr);

    /// The layout choices ("3-D Only", "Four-Up"), exclusive, for the View menu.
    QList<QAction*> layoutActions() const;
    void setFourUp(bool on);
    bool fourUp() const;

    /// The panes: 0 axial (z), 1 coronal (y), 2 sagittal (x).
    SlicePane* pane(int i) const { return panes_[std::size_t(i)]; }
    /// The crosshair: the sample (i, j, k) the three slices pass through.
    ivec3 cursor() const { return cursor_; }
    void setCursor(ivec3 ijk);
    /// The sample index the pane's slice passes through (along the grid axis across its plane).
    int sliceIndex(int pane) const;
    /// Moves pane `pane`'s slice by `slices` samples (clamped to the grid).
    void step(int pane, int slices);
    /// Where pane `pane`'s slice lies when placed by its position box (the CLI's `at`, in the
    /// user's terms: model::sliceWorldOfAt; on an ocean grid the depth in metres, the latitude,
    /// the longitude); unset: at the crosshair's sample (`index`).
    std::optional<double> at(int pane) const { return at_[std::size_t(pane)]; }
    /// Places pane `pane`'s slice at `at` (clamped to the grid, model::sliceAtRange) and the
    /// crosshair at the sample nearest to it; moving the slice by a sample again (wheel, keys,
    /// a click in another pane) goes back to samples.
    void setAt(int pane, double at);
    /// The window in use (invalid: a colour map, off patient volumes) and where it comes from.
    ValueWindow window() const { return window_; }
    QString windowSource() const { return windowSource_; }
    /// A preset (CtPresets.h), or "" for the automatic window.
    void choosePreset(const QString& name);
    /// The window as a session keeps it: "" automatic, a preset's name, or "C,W" (dragged).
    std::string windowText() const;
    /// Sets the window from windowText()'s form; false when `text` is none of them.
    bool setWindowText(const std::string& text);

    /// The CLI's arguments that read the field the studio read (model: inputArguments for
    /// `slice`): INPUT and its --var, --time, --series, --region, ...
    void setReadArguments(std::function<QStringList()> arguments) { readArguments_ = std::move(arguments); }

    /// Picks the surface point under `devicePixel` of the last exact 3-D frame and moves the
    /// crosshair to the sample nearest to it. False when nothing was hit there.
    bool pickSurface(QPointF devicePixel);
    /// The crosshair's position in the 3-D view (device pixels) for `camera`, when in front of it.
    std::optional<QPointF> crosshairIn(const Camera& camera) const;

    /// What the probe read last: the value, and the world (LPS for patient volumes) position.
    struct Probe {
        bool valid = false;
        double value = 0.0;
        dvec3 world{0.0};
        QString text;
    };
    const Probe& probe() const { return probe_; }
    /// The probe at `imagePixel` of pane `pane` (as the pointer does).
    void probeAt(int pane, QPointF imagePixel);

    /// The `octrace slice` arguments (without program and command) that write pane `pane`'s
    /// image to `output`.
    QStringList commandLine(int pane, const QString& output) const;

signals:
    /// The crosshair or a pane's position moved.
    void cursorChanged();
    void windowChanged();
    void layoutChanged(bool fourUp);

private:
    void setField(std::shared_ptr<const ScalarField> field, const QString& input);
    void renderPane(int i);
    void renderPanes();
    void updateWindowControls();
    model::SliceSpec specFor(int pane) const;
    void dragWindow(int dx, int dy);
    /// A window of the user's own (dragged, or a session's "C,W").
    void setCustomWindow(ValueWindow w);
    /// The sample nearest to world point `p`, clamped to the grid.
    ivec3 nearestSample(const dvec3& p) const;
    /// The crosshair's world point: the sample, moved onto the planes placed by `at`.
    dvec3 crosshairWorld() const;
    /// Moves the crosshair; the panes whose slice it moves lose their `at`.
    void moveCursor(ivec3 ijk, bool keepAt);
    void updateAtBoxes();

    Engine& engine_;
    std::shared_ptr<const ScalarField> field_;
    QString input_;
    ivec3 cursor_{0};
    ValueWindow window_, autoWindow_;
    std::string windowName_;  // a preset's name, else ""
    QString windowSource_;
    std::array<SlicePane*, 3> panes_{};
    QWidget* threeD_;
    QWidget* bar_;
    QGridLayout* grid_;
    QComboBox* windowCombo_;
    QToolButton* windowLevelButton_;
    QLabel *windowLabel_, *probeLabel_;
    std::array<QLabel*, 3> atLabels_{};
    std::array<QDoubleSpinBox*, 3> atBoxes_{};
    std::array<std::optional<double>, 3> at_;
    std::function<QStringList()> readArguments_;
    QActionGroup* layoutGroup_;
    QAction *threeDOnly_, *fourUpAction_;
    Probe probe_;
    Frame pickFrame_;  // the last exact 3-D frame and its camera
    Camera pickCamera_;
    bool updating_ = false;
};

}  // namespace octrace::studio
