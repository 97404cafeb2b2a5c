#include "SliceViews.h"

#include "Engine.h"

#include "octrace/build/CtPresets.h"
#include "octrace/model/OptionTable.h"
#include "octrace/model/Surface.h"
#include "octrace/util/Error.h"

#include <QAction>
#include <QActionGroup>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace octrace::studio {
namespace {

/// Numbers on a command line: 17 significant digits, an exact round trip.
QString exact(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return QString::fromLatin1(buf);
}

QString text(double v) { return QString::number(v, 'g', 6); }

/// The pane's plane: patient planes for patient volumes, else the world's z, y, x.
SlicePlane planeOf(const ScalarField* f, int pane) {
    constexpr SlicePlane patient[3] = {SlicePlane::Axial, SlicePlane::Coronal, SlicePlane::Sagittal};
    constexpr SlicePlane world[3] = {SlicePlane::Z, SlicePlane::Y, SlicePlane::X};
    return (f && !f->patientLps ? world : patient)[pane];
}

constexpr int kCustom = 1000;  // the window combo's item of a dragged window

/// The same variable on the same grid (dims, spacing, origin, direction, axis positions): another
/// time step or volume of the input read before, where the slices' places and window still hold.
bool sameGrid(const ScalarField& a, const ScalarField& b) {
    return a.name == b.name && a.units == b.units && a.dims == b.dims && a.origin == b.origin && a.spacing == b.spacing &&
           a.direction == b.direction && a.coords == b.coords && a.patientLps == b.patientLps;
}

}  // namespace

SliceViews::SliceViews(QWidget* threeD, Engine& engine, QWidget* parent) : QWidget(parent), engine_(engine), threeD_(threeD) {
    auto* outer = new QVBoxLayout(this);
    outer->setContentsMargins(0, 0, 0, 0);
    outer->setSpacing(2);
    bar_ = new QWidget(this);
    auto* barRows = new QVBoxLayout(bar_);
    barRows->setContentsMargins(4, 2, 4, 2);
    barRows->setSpacing(2);
    auto* barLayout = new QHBoxLayout;
    barRows->addLayout(barLayout);
    barLayout->addWidget(new QLabel(tr("Window"), bar_));
    windowCombo_ = new QComboBox(bar_);
    windowCombo_->setObjectName(QStringLiteral("sliceWindowCombo"));
    windowCombo_->setToolTip(tr("The slices' display window: automatic (the file's window, else the volume's 1st to 99th "
                                "percentile), or a CT preset (volumes in HU); right drag in a slice sets it by hand"));
    windowCombo_->addItem(tr("Automatic"), QString());
    for (const auto& p : ctWindowPresets()) windowCombo_->addItem(QString::fromLatin1(p.name), QString::fromLatin1(p.name));
    windowCombo_->addItem(tr("Custom (dragged)"), kCustom);
    barLayout->addWidget(windowCombo_);
    windowLevelButton_ = new QToolButton(bar_);
    windowLevelButton_->setObjectName(QStringLiteral("windowLevelButton"));
    windowLevelButton_->setText(tr("W/L drag"));
    windowLevelButton_->setCheckable(true);
    windowLevelButton_->setToolTip(tr("Left drag in a slice sets the window (horizontal: width, vertical: level) instead of "
                                      "moving the crosshair; right drag always does"));
    barLayout->addWidget(windowLevelButton_);
    windowLabel_ = new QLabel(bar_);
    windowLabel_->setObjectName(QStringLiteral("sliceWindowLabel"));
    barLayout->addWidget(windowLabel_, 1);
    // Each pane's position as the CLI's `at` takes it (its help from the options table; the
    // range is the grid's): an ocean field's depth, latitude and longitude, else mm or world units.
    auto* atRow = new QHBoxLayout;
    barRows->addLayout(atRow);
    for (int i = 0; i < 3; ++i) {
        atLabels_[std::size_t(i)] = new QLabel(bar_);
        auto* box = atBoxes_[std::size_t(i)] = new QDoubleSpinBox(bar_);
        box->setObjectName(QStringLiteral("sliceAt%1").arg(i));
        box->setDecimals(4);
        box->setKeyboardTracking(false);  // a typed number is taken on Enter, not at each keystroke
        box->setFocusPolicy(Qt::StrongFocus);
        box->setToolTip(QString::fromLatin1(model::opt::at.help));
        connect(box, &QDoubleSpinBox::valueChanged, this, [this, i](double v) {
            if (!updating_) setAt(i, v);
        });
        atRow->addWidget(atLabels_[std::size_t(i)]);
        atRow->addWidget(box);
    }
    atRow->addStretch(1);
    outer->addWidget(bar_);

    auto* grid = grid_ = new QGridLayout;
    grid->setSpacing(2);
    for (int i = 0; i < 3; ++i) {
        auto* pane = new SlicePane(planeOf(nullptr, i), this);
        pane->setObjectName(QStringLiteral("slicePane%1").arg(i));
        panes_[std::size_t(i)] = pane;
        connect(pane, &SlicePane::stepBy, this, [this, i](int n) { step(i, n); });
        connect(pane, &SlicePane::resized, this, [this, i] { renderPane(i); });
        connect(pane, &SlicePane::pressedAt, this, [this, i](QPointF px) {
            const SlicePane* p = panes_[std::size_t(i)];
            if (!field_ || !p->hasSlice()) return;
            // The crosshair moves in the pane's plane; the pane's own slice stays.
            const int across = sliceGridAxis(*field_, p->plane());
            ivec3 c = nearestSample(p->content().result.view.world(px.x() - 0.5, px.y() - 0.5));
            c[across] = cursor_[across];
            setCursor(c);
            probeAt(i, px);
        });
        connect(pane, &SlicePane::pointerAt, this, [this, i](QPointF px) { probeAt(i, px); });
        connect(pane, &SlicePane::windowDrag, this, &SliceViews::dragWindow);
    }
    // 3D Slicer's four-up: axial (red) upper left, 3-D upper right, sagittal (yellow) lower
    // left, coronal (green) lower right.
    grid->addWidget(panes_[0], 0, 0);
    grid->addWidget(threeD_, 0, 1);
    grid->addWidget(panes_[2], 1, 0);
    grid->addWidget(panes_[1], 1, 1);
    // Four equal quarters, whatever the views' own size hints.
    for (QWidget* w : {threeD_, static_cast<QWidget*>(panes_[0]), static_cast<QWidget*>(panes_[1]), static_cast<QWidget*>(panes_[2])})
        w->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Ignored);
    outer->addLayout(grid, 1);
    probeLabel_ = new QLabel(this);
    probeLabel_->setObjectName(QStringLiteral("probeLabel"));
    probeLabel_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    outer->addWidget(probeLabel_);

    layoutGroup_ = new QActionGroup(this);
    threeDOnly_ = new QAction(tr("&3-D Only Layout"), layoutGroup_);
    threeDOnly_->setObjectName(QStringLiteral("layout3d"));
    fourUpAction_ = new QAction(tr("&Four-Up Layout"), layoutGroup_);
    fourUpAction_->setObjectName(QStringLiteral("layoutFourUp"));
    fourUpAction_->setToolTip(tr("Axial, coronal and sagittal slices beside the 3-D view (3D Slicer's four-up)"));
    for (QAction* a : layoutGroup_->actions()) a->setCheckable(true);
    threeDOnly_->setChecked(true);
    connect(fourUpAction_, &QAction::toggled, this, &SliceViews::setFourUp);

    connect(windowCombo_, &QComboBox::currentIndexChanged, this, [this](int) {
        if (updating_ || windowCombo_->currentData().toInt() == kCustom) return;
        choosePreset(windowCombo_->currentData().toString());
    });
    connect(windowLevelButton_, &QToolButton::toggled, this, [this](bool on) {
        for (SlicePane* p : panes_) p->setWindowLevelMode(on);
    });
    connect(&engine_, &Engine::inputLoaded, this, [this] { setField(engine_.field(), engine_.info().input); });
    connect(&engine_, &Engine::frameReady, this, [this](const FrameResult& r) {
        if (r.preview || r.panes.empty() || !fourUp()) return;  // picking is for the four-up layout
        pickFrame_ = r.panes[0].frame;
        pickCamera_ = r.camera;
    });
    setFourUp(false);
    setField(nullptr, QString());
}

QList<QAction*> SliceViews::layoutActions() const { return {threeDOnly_, fourUpAction_}; }

bool SliceViews::fourUp() const { return fourUpAction_->isChecked(); }

void SliceViews::setFourUp(bool on) {
    if (fourUpAction_->isChecked() != on) (on ? fourUpAction_ : threeDOnly_)->setChecked(true);
    for (SlicePane* p : panes_) p->setVisible(on);
    // Four equal quarters, or the 3-D view's column and row alone.
    grid_->setColumnStretch(0, on ? 1 : 0);
    grid_->setRowStretch(1, on ? 1 : 0);
    grid_->setColumnStretch(1, 1);
    grid_->setRowStretch(0, 1);
    bar_->setVisible(on);
    probeLabel_->setVisible(on);
    if (on) renderPanes();
    emit layoutChanged(on);
}

void SliceViews::setField(std::shared_ptr<const ScalarField> field, const QString& input) {
    // Another time step or volume of the same input (cine): the crosshair, the panes' positions
    // and a preset or dragged window stay; only the slices are drawn anew.
    if (field && field_ && input == input_ && sameGrid(*field, *field_)) {
        field_ = std::move(field);
        probe_ = {};
        probeLabel_->clear();
        if (field_->patientLps) {
            autoWindow_ = field_->window.valid() ? field_->window : engine_.info().percentileWindow;
            const bool automatic = windowName_.empty() && windowCombo_->currentData().toInt() != kCustom;
            if (automatic) window_ = autoWindow_;  // this volume's, as `slice --volume N` chooses it
        }
        updateWindowControls();
        updateAtBoxes();
        renderPanes();
        emit cursorChanged();
        emit windowChanged();
        return;
    }
    field_ = std::move(field);
    input_ = input;
    at_ = {};
    probe_ = {};
    probeLabel_->clear();
    window_ = autoWindow_ = {};
    windowName_.clear();
    windowSource_.clear();
    if (field_) {
        for (int i = 0; i < 3; ++i) panes_[std::size_t(i)]->setPlane(planeOf(field_.get(), i));
        cursor_ = ivec3(field_->dims.x / 2, field_->dims.y / 2, field_->dims.z / 2);  // the CLI's default index, n/2
        if (field_->patientLps) {
            // The file's window (DICOM), else the 1st to 99th percentile (MR has no presets).
            if (field_->window.valid()) {
                autoWindow_ = field_->window;
                windowSource_ = tr("the file's window");
            } else {
                autoWindow_ = engine_.info().percentileWindow;
                windowSource_ = tr("1st to 99th percentile");
            }
            window_ = autoWindow_;
        }
    }
    updating_ = true;
    windowCombo_->setCurrentIndex(0);
    updating_ = false;
    updateWindowControls();
    updateAtBoxes();
    renderPanes();
    emit cursorChanged();
    emit windowChanged();
}

void SliceViews::updateWindowControls() {
    const bool patient = field_ && field_->patientLps;
    const bool hounsfield = patient && field_->units == "HU";
    windowCombo_->setEnabled(patient);
    windowLevelButton_->setEnabled(patient);
    // The presets are in HU: only for a volume in HU (the CLI refuses them for others too).
    for (int i = 1; i <= int(ctWindowPresets().size()); ++i) {
        windowCombo_->setItemData(i, hounsfield ? QVariant() : QVariant(0), Qt::UserRole - 1);
    }
    if (!window_.valid()) windowLabel_->setText(patient || !field_ ? QString() : tr("colour map (not a patient volume)"));
    else windowLabel_->setText(tr("centre %1, width %2 (%3)").arg(text(window_.centre), text(window_.width), windowSource_));
}

void SliceViews::choosePreset(const QString& name) {
    if (!field_ || !field_->patientLps) return;
    if (name.isEmpty()) {
        window_ = autoWindow_;
        windowName_.clear();
        windowSource_ = field_->window.valid() ? tr("the file's window") : tr("1st to 99th percentile");
    } else {
        const auto w = ctWindowPreset(name.toStdString());
        if (!w) return;
        window_ = *w;
        windowName_ = name.toStdString();
        windowSource_ = tr("preset %1").arg(name);
    }
    updating_ = true;
    windowCombo_->setCurrentIndex(std::max(0, windowCombo_->findData(name)));
    updating_ = false;
    updateWindowControls();
    renderPanes();
    emit windowChanged();
}

std::string SliceViews::windowText() const {
    if (!window_.valid()) return {};
    if (windowCombo_->currentData().toInt() == kCustom)
        return (exact(window_.centre) + QLatin1Char(',') + exact(window_.width)).toStdString();
    return windowName_;
}

bool SliceViews::setWindowText(const std::string& text) {
    if (!field_ || !field_->patientLps) return text.empty();
    const QString t = QString::fromStdString(text);
    if (t.isEmpty() || ctWindowPreset(text)) {
        if (!t.isEmpty() && field_->units != "HU") return false;  // the presets are in HU, as the CLI says
        choosePreset(t);
        return true;
    }
    ValueWindow w;
    try {
        w = model::displayWindow(text);  // "C,W", as `window` takes it
    } catch (const UsageError&) {
        return false;
    }
    if (!w.valid()) return false;
    setCustomWindow(w);
    return true;
}

void SliceViews::setCustomWindow(ValueWindow w) {
    window_ = w;
    windowName_.clear();
    windowSource_ = tr("dragged");
    updating_ = true;
    windowCombo_->setCurrentIndex(windowCombo_->findData(kCustom));
    updating_ = false;
    updateWindowControls();
    renderPanes();
    emit windowChanged();
}

void SliceViews::dragWindow(int dx, int dy) {
    if (!field_ || !window_.valid()) return;
    // As 3D Slicer: horizontal drag widens the window, vertical drag (down) lowers the level;
    // a drag across 500 pixels sweeps the volume's range.
    const auto [lo, hi] = field_->validRange();
    const double perPixel = std::max(double(hi) - double(lo), 1e-30) / 500.0;
    setCustomWindow({window_.centre - dy * perPixel, std::max(window_.width + dx * perPixel, perPixel)});
}

ivec3 SliceViews::nearestSample(const dvec3& p) const {
    const dvec3 g = sliceGridPosition(*field_, p);
    ivec3 out;
    for (int a = 0; a < 3; ++a) out[a] = std::clamp(int(std::lround(g[a])), 0, field_->dims[a] - 1);
    return out;
}

void SliceViews::setCursor(ivec3 ijk) { moveCursor(ijk, false); }

void SliceViews::moveCursor(ivec3 ijk, bool keepAt) {
    if (!field_) return;
    for (int a = 0; a < 3; ++a) ijk[a] = std::clamp(ijk[a], 0, field_->dims[a] - 1);
    if (ijk == cursor_ && !keepAt) return;
    // A pane moved by a sample (wheel, keys, a click elsewhere) is at that sample again.
    if (!keepAt)
        for (int i = 0; i < 3; ++i) {
            const int axis = sliceGridAxis(*field_, panes_[std::size_t(i)]->plane());
            if (ijk[axis] != cursor_[axis]) at_[std::size_t(i)].reset();
        }
    cursor_ = ijk;
    updateAtBoxes();
    renderPanes();
    emit cursorChanged();
}

void SliceViews::setAt(int i, double at) {
    if (!field_) return;
    const SlicePlane plane = panes_[std::size_t(i)]->plane();
    const auto [lo, hi] = slicePositionRange(*field_, plane);
    double world = model::sliceWorldOfAt(*field_, plane, at);
    if (world < lo || world > hi) {  // beyond the grid (the CLI refuses it): its edge
        world = std::clamp(world, lo, hi);
        at = model::sliceAtOfWorld(*field_, plane, world);
    }
    at_[std::size_t(i)] = at;
    dvec3 p = field_->worldFromGrid(cursor_.x, cursor_.y, cursor_.z);
    p[sliceNormalAxis(plane)] = world;
    ivec3 c = cursor_;
    const int axis = sliceGridAxis(*field_, plane);
    c[axis] = nearestSample(p)[axis];
    moveCursor(c, true);
}

dvec3 SliceViews::crosshairWorld() const {
    dvec3 w = field_->worldFromGrid(cursor_.x, cursor_.y, cursor_.z);
    for (int i = 0; i < 3; ++i)
        if (const auto& a = at_[std::size_t(i)]) {
            const SlicePlane plane = panes_[std::size_t(i)]->plane();
            w[sliceNormalAxis(plane)] = model::sliceWorldOfAt(*field_, plane, *a);
        }
    return w;
}

void SliceViews::updateAtBoxes() {
    updating_ = true;
    for (int i = 0; i < 3; ++i) {
        QDoubleSpinBox* box = atBoxes_[std::size_t(i)];
        QLabel* label = atLabels_[std::size_t(i)];
        box->setEnabled(bool(field_));
        if (!field_) continue;
        const SlicePlane plane = panes_[std::size_t(i)]->plane();
        const int n = sliceNormalAxis(plane);
        const auto [lo, hi] = model::sliceAtRange(*field_, plane);
        const bool geographic = field_->geographic.valid, polar = geographic && field_->geographic.polar() && n != 2;
        QString name = QString::fromLatin1(slicePlaneName(plane)), suffix;
        if (geographic && !polar) {
            constexpr const char* names[3] = {"longitude", "latitude", "depth"};
            name = QString::fromLatin1(names[n]);
            suffix = n == 2 ? QStringLiteral(" m") : n == 1 ? QStringLiteral(" \u00b0N") : QStringLiteral(" \u00b0E");
        } else if (polar) {
            suffix = QStringLiteral(" km");
        } else if (field_->patientLps) {
            suffix = QStringLiteral(" mm");
        }
        label->setText(name);
        box->setSuffix(suffix);
        box->setRange(lo, hi);
        box->setSingleStep(std::max((hi - lo) / std::max(1, field_->dims[sliceGridAxis(*field_, plane)] - 1), 1e-4));
        // The `at` given (in the grid's own longitudes), else the crosshair's sample.
        const double world = at_[std::size_t(i)] ? model::sliceWorldOfAt(*field_, plane, *at_[std::size_t(i)])
                                                 : slicePositionOfIndex(*field_, plane, sliceIndex(i));
        box->setValue(model::sliceAtOfWorld(*field_, plane, world));
    }
    updating_ = false;
}

int SliceViews::sliceIndex(int pane) const {
    if (!field_) return 0;
    return cursor_[sliceGridAxis(*field_, panes_[std::size_t(pane)]->plane())];
}

void SliceViews::step(int pane, int slices) {
    if (!field_) return;
    ivec3 c = cursor_;
    c[sliceGridAxis(*field_, panes_[std::size_t(pane)]->plane())] += slices;
    setCursor(c);
}

model::SliceSpec SliceViews::specFor(int i) const {
    const SlicePane* p = panes_[std::size_t(i)];
    model::SliceSpec s;
    s.input = input_.toStdString();
    s.plane = p->plane();
    if (at_[std::size_t(i)]) s.at = at_[std::size_t(i)];
    else s.index = sliceIndex(i);
    const QSize size = p->imageSize();
    s.width = size.width();
    s.height = size.height();
    if (window_.valid()) {
        s.window = window_;
        s.windowName = windowName_.empty() ? (exact(window_.centre) + QLatin1Char(',') + exact(window_.width)).toStdString() : windowName_;
    }
    return s;
}

QStringList SliceViews::commandLine(int i, const QString& output) const {
    const model::SliceSpec s = specFor(i);
    QStringList a = readArguments_ ? readArguments_() : QStringList{input_};
    a << QStringLiteral("--plane") << QString::fromLatin1(slicePlaneName(*s.plane));
    if (s.at) a << QStringLiteral("--at") << exact(*s.at);
    else a << QStringLiteral("--index") << QString::number(*s.index);
    a << QStringLiteral("--size") << QStringLiteral("%1x%2").arg(s.width).arg(s.height);
    if (window_.valid()) a << QStringLiteral("--window") << QString::fromStdString(s.windowName);
    a << QStringLiteral("-o") << output;
    return a;
}

void SliceViews::renderPanes() {
    for (int i = 0; i < 3; ++i) renderPane(i);
}

void SliceViews::renderPane(int i) {
    SlicePane* p = panes_[std::size_t(i)];
    if (!p->isVisible()) return;
    if (!field_) {
        p->setMessage(engine_.info().input.isEmpty() ? tr("No volume: File > Open") : tr("No field to slice: an octree file or a city model"));
        return;
    }
    try {
        SlicePane::Content c;
        c.result = model::renderSlice(*field_, specFor(i));
        c.image = toImage(c.result.image);
        const SliceView& v = c.result.view;
        const dvec3 R = v.screenRight(), U = v.screenUp();
        c.letters[0] = QString::fromStdString(model::sliceDirectionName(*field_, R));
        c.letters[1] = QString::fromStdString(model::sliceDirectionName(*field_, -R));
        c.letters[2] = QString::fromStdString(model::sliceDirectionName(*field_, U));
        c.letters[3] = QString::fromStdString(model::sliceDirectionName(*field_, -U));
        c.scaleBar = model::sliceScaleBar(*field_, v, false);  // `slice --figure`'s: always on patient volumes
        const dvec3 d = crosshairWorld() - v.topLeft;
        const double ps2 = v.pixelSize * v.pixelSize;
        c.crosshair = QPointF(glm::dot(d, v.right) / ps2 + 0.5, glm::dot(d, v.down) / ps2 + 0.5);
        const int n = field_->dims[v.gridAxis];
        c.caption = at_[std::size_t(i)] ? QStringLiteral("%1  %2").arg(QString::fromLatin1(slicePlaneName(v.plane)),
                                                                        QString::fromStdString(model::slicePositionText(*field_, v)))
                                        : QStringLiteral("%1  %2 / %3").arg(QString::fromLatin1(slicePlaneName(v.plane))).arg(sliceIndex(i)).arg(n - 1);
        p->setContent(std::move(c));
    } catch (const std::exception& e) {
        p->setMessage(QString::fromStdString(model::sayForStudio(e.what())));
    }
}

void SliceViews::probeAt(int i, QPointF px) {
    const SlicePane* p = panes_[std::size_t(i)];
    if (!field_ || !p->hasSlice()) return;
    const model::SliceResult& r = p->content().result;
    const int x = int(std::floor(px.x())), y = int(std::floor(px.y()));
    if (x < 0 || y < 0 || x >= r.values.width || y >= r.values.height) return;
    const std::size_t k = std::size_t(y) * std::size_t(r.values.width) + std::size_t(x);
    probe_ = {};
    probe_.world = r.view.world(x, y);  // the pixel's centre
    const SliceSample state = r.values.state[k];
    probe_.valid = state == SliceSample::Valid;
    probe_.value = r.values.values[k];
    const dvec3& w = probe_.world;
    const QString units = field_->units.empty() ? QString() : QLatin1Char(' ') + QString::fromStdString(field_->units);
    const QString value = state == SliceSample::Valid    ? text(probe_.value) + units
                          : state == SliceSample::Masked ? tr("masked")
                                                         : tr("outside the volume");
    const dvec3 g = sliceGridPosition(*field_, w);
    const QString sample = tr("sample (%1, %2, %3)").arg(text(g.x), text(g.y), text(g.z));
    if (field_->patientLps)
        // LPS is DICOM's patient frame (the world here); RAS (NIfTI, 3D Slicer) negates x and y.
        probe_.text = tr("%1: %2 at LPS (%3, %4, %5) mm, RAS (%6, %7, %5) mm, %8")
                          .arg(QString::fromLatin1(slicePlaneName(r.view.plane)), value, text(w.x), text(w.y), text(w.z),
                               text(-w.x + 0.0), text(-w.y + 0.0), sample);
    else
        probe_.text = tr("%1: %2 at (%3, %4, %5), %6")
                          .arg(QString::fromLatin1(slicePlaneName(r.view.plane)), value, text(w.x), text(w.y), text(w.z), sample);
    probeLabel_->setText(probe_.text);
}

bool SliceViews::pickSurface(QPointF px) {
    if (!field_ || pickFrame_.width == 0) return false;
    const int x = int(std::floor(px.x())), y = int(std::floor(px.y()));
    if (x < 0 || y < 0 || x >= pickFrame_.width || y >= pickFrame_.height) return false;
    const std::size_t k = pickFrame_.pixel(x, y);
    if (pickFrame_.hitId[k] == kNoHit || !std::isfinite(pickFrame_.depth[k])) return false;
    const Ray ray = pickCamera_.primaryRay(x, y);
    setCursor(nearestSample(ray.origin + double(pickFrame_.depth[k]) * ray.direction));
    return true;
}

std::optional<QPointF> SliceViews::crosshairIn(const Camera& camera) const {
    if (!field_) return std::nullopt;
    const dvec3 w = crosshairWorld();
    const RayGenerator rays(camera);
    const dvec3 d = w - rays.eye();
    const double cz = glm::dot(d, rays.back());
    if (!rays.orthographic() && cz >= 0.0) return std::nullopt;  // behind the eye
    double x = 0.0, y = 0.0;
    rays.toPixel(glm::dot(d, rays.right()), glm::dot(d, rays.up()), cz, x, y);
    return QPointF(x, y);
}

}  // namespace octrace::studio
