#include "MainWindow.h"

#include "OptionWidgets.h"

#include "HistogramView.h"
#include "Navigation.h"
#include "RenderView.h"
#include "Session.h"
#include "SidePanel.h"
#include "SliceViews.h"
#include "StepSlider.h"
#include "SurfelView.h"
#include "ViewInput.h"

#include "octrace/model/SolidSpec.h"
#include "octrace/csg/Solid.h"
#include "octrace/util/Error.h"

#include "octrace/io/FieldReader.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/Renderer.h"
#include "octrace/build/AnalyticField.h"
#include "octrace/build/CtPresets.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Log.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QClipboard>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QInputDialog>
#include <QLabel>
#include <QLineEdit>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QSlider>
#include <QSpinBox>
#include <QSplitter>
#include <QStackedWidget>
#include <QStandardItemModel>
#include <QStatusBar>
#include <QToolBar>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>
#include <variant>
#include <vector>

namespace octrace::studio {
namespace {

constexpr int kSliderSteps = 1000;
constexpr int kMaxRecent = 8;
const char* kRecentKey = "recentFiles";

QString statsText(const PaneFrame& p, double fullMs, bool preview, int level) {
    const RenderStats& s = p.stats;
    QString t = QStringLiteral("%1  %2x%3\n%4 ms/frame").arg(QString::fromStdString(s.renderer)).arg(p.frame.width)
                    .arg(p.frame.height).arg(s.renderMs, 0, 'f', 1);
    if (p.tracesRays)
        t += QStringLiteral("\n%1 us/ray").arg(s.rays ? s.renderMs * 1000.0 / double(s.rays) : 0.0, 0, 'f', 3);
    else
        t += QStringLiteral("\n%1 footprints").arg(s.voxelsSplatted);
    if (fullMs > 0.0 && s.renderMs > 0.0) t += QStringLiteral("\n%1x over full").arg(fullMs / s.renderMs, 0, 'f', 2);
    if (preview) t += QStringLiteral("\npreview (level %1, half size)").arg(level);
    return t;
}

}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
    setWindowTitle(tr("octrace studio"));
    setAcceptDrops(true);
    buildTimer_.setSingleShot(true);
    buildTimer_.setInterval(150);
    connect(&buildTimer_, &QTimer::timeout, this, [this] {
        if (engine_.hasField() && state_.iso) engine_.rebuild(state_);
        else if (!engine_.hasField() && engine_.tree()) load(state_);  // an octree file or a city: read again
    });
    exactTimer_.setSingleShot(true);
    exactTimer_.setInterval(250);
    connect(&exactTimer_, &QTimer::timeout, this, [this] { requestRender(false); });

    auto* splitter = new QSplitter(this);
    // The right pane: a CPU renderer's frames, or the OpenGL surfel view.
    secondPane_ = new QStackedWidget(splitter);
    for (int i = 0; i < 2; ++i) {
        views_[i] = new RenderView(splitter);
        views_[i]->setObjectName(i == 0 ? QStringLiteral("mainView") : QStringLiteral("secondView"));
        if (i == 0) splitter->insertWidget(0, views_[i]);
        else secondPane_->addWidget(views_[i]);
        connectNavigation(views_[i]->input());
        if (i == 0) connect(views_[i], &RenderView::painted, this, &MainWindow::framePainted);
        connect(views_[i], &RenderView::resized, this, [this] { exactTimer_.start(); });
    }
    // The OpenGL surfel view is made when first shown (surfelView()): an OpenGL widget in a window
    // makes Qt compose the whole window with OpenGL, which on a machine without a GPU (Mesa's
    // llvmpipe) took about 45% of the studio's CPU time while orbiting in the CPU renderers' view.
    secondPane_->hide();
    // The 3-D views alone, or in the four-up layout with the slice panes.
    slices_ = new SliceViews(splitter, engine_, this);
    setCentralWidget(slices_);
    slices_->setReadArguments([this] {
        QStringList a;
        for (const std::string& s : inputArguments(state_, "slice")) a << QString::fromStdString(s);
        return a;
    });
    connect(slices_, &SliceViews::cursorChanged, this, [this] {
        keepSlices();
        showCrosshair();
    });
    connect(slices_, &SliceViews::windowChanged, this, &MainWindow::keepSlices);
    connect(slices_, &SliceViews::layoutChanged, this, [this] {
        keepSlices();
        showCrosshair();
        exactTimer_.start();  // the 3-D view's size changed
    });
    connect(views_[0]->input(), &ViewInput::clicked, this, [this](QPointF pos) {
        if (slices_->fourUp()) slices_->pickSurface(pos * views_[0]->devicePixelRatioF());
    });

    auto* dock = new QDockWidget(tr("Surface"), this);
    dock->setObjectName(QStringLiteral("surfaceDock"));
    auto* panel = new SidePanel(buildControls(), dock);
    panel->setObjectName(QStringLiteral("sidePanel"));
    dock->setWidget(panel);
    addDockWidget(Qt::LeftDockWidgetArea, dock);

    auto* msgDock = new QDockWidget(tr("Messages"), this);
    msgDock->setObjectName(QStringLiteral("messagesDock"));
    messages_ = new QPlainTextEdit(msgDock);
    messages_->setReadOnly(true);
    messages_->setMaximumBlockCount(500);
    msgDock->setWidget(messages_);
    addDockWidget(Qt::BottomDockWidgetArea, msgDock);
    resizeDocks({msgDock}, {80}, Qt::Vertical);
    resizeDocks({dock}, {340}, Qt::Horizontal);

    statusLabel_ = new QLabel(this);
    progress_ = new QProgressBar(this);
    progress_->setObjectName(QStringLiteral("progress"));
    progress_->setMaximumWidth(220);
    progress_->setRange(0, 100);
    progress_->hide();
    cancelButton_ = new QPushButton(tr("Cancel"), this);
    cancelButton_->setObjectName(QStringLiteral("cancelButton"));
    cancelButton_->setEnabled(false);
    cancelButton_->setToolTip(tr("Stop reading or building (Esc)"));
    cancelButton_->setShortcut(Qt::Key_Escape);
    connect(cancelButton_, &QPushButton::clicked, this, [this] { engine_.cancel(); });
    latencyLabel_ = new QLabel(this);
    latencyLabel_->setObjectName(QStringLiteral("latencyLabel"));
    latencyLabel_->setToolTip(tr("Input to paint: from the mouse or key event that moved the camera to the end of "
                                 "painting the first frame that shows it (the longest wait among the events that "
                                 "frame answered)"));
    statusBar()->addWidget(statusLabel_, 1);
    statusBar()->addPermanentWidget(latencyLabel_);
    statusBar()->addPermanentWidget(progress_);
    statusBar()->addPermanentWidget(cancelButton_);

    buildMenus();

    connect(&engine_, &Engine::progress, this, [this](const QString& stage, double f) {
        statusLabel_->setText(stage);
        progress_->show();
        if (f < 0.0) progress_->setRange(0, 0);  // busy
        else {
            progress_->setRange(0, 100);
            progress_->setValue(int(f * 100.0));
        }
        cancelButton_->setEnabled(engine_.building());
    });
    connect(&engine_, &Engine::inputLoaded, this, &MainWindow::onInputLoaded);
    connect(&engine_, &Engine::surfaceBuilt, this, &MainWindow::onSurfaceBuilt);
    connect(&engine_, &Engine::frameReady, this, &MainWindow::onFrame);
    connect(&engine_, &Engine::failed, this, [this](const QString& m) {
        restoreSlices_ = false;
        stepAbandoned();
        progress_->hide();
        cancelButton_->setEnabled(engine_.building());
        showMessage(m, true);
    });
    connect(&engine_, &Engine::cancelled, this, [this] {
        restoreSlices_ = false;
        stepAbandoned();
        progress_->hide();
        cancelButton_->setEnabled(false);
        if (engine_.tree()) {  // the controls show the surface that stays
            state_.iso = engine_.iso();
            setIsoControls(engine_.iso());
            showBuiltDepth();
        }
        showMessage(tr("Cancelled; the previous surface stays"));
    });
    connect(&engine_, &Engine::exported, this, [this](const QString&, const QString& summary) {
        progress_->hide();
        showMessage(tr("Exported %1").arg(summary));
    });

    // Library messages (warnings of the readers) go to the Messages panel, from any thread.
    log::setWording([](const std::string& text) { return model::sayForStudio(text); });
    log::setSink([this](log::Level level, const std::string& text) {
        QMetaObject::invokeMethod(this, [this, level, t = QString::fromStdString(text)] {
            messages_->appendPlainText((level >= log::Level::Warning ? tr("warning: ") : QString()) + t);
        }, Qt::QueuedConnection);
    });
    updateRecentMenu();
    resize(1200, 800);
}

MainWindow::~MainWindow() {
    log::setSink({});
    log::setWording({});
}

void MainWindow::connectNavigation(ViewInput* input) {
    connect(input, &ViewInput::orbitBy, this, [this](double yaw, double pitch) {
        latency_.input(LatencyMeter::Input::Move);
        Camera c = viewCamera();
        orbit(c, yaw, pitch);
        cameraMoved(c);
    });
    connect(input, &ViewInput::panBy, this, [this](double dx, double dy, int viewHeight) {
        latency_.input(LatencyMeter::Input::Move);
        Camera c = viewCamera();
        pan(c, dx, dy, viewHeight);
        cameraMoved(c);
    });
    connect(input, &ViewInput::dollyBy, this, [this](double f) {
        latency_.input(LatencyMeter::Input::Move);
        Camera c = viewCamera();
        dolly(c, f);
        cameraMoved(c);
    });
    connect(input, &ViewInput::interactionFinished, this, [this] {
        latency_.input(LatencyMeter::Input::Finish);
        exactTimer_.stop();
        requestRender(false);
    });
}

void MainWindow::buildMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    QAction* open = file->addAction(tr("&Open..."), this, &MainWindow::chooseOpen);
    open->setShortcut(QKeySequence::Open);
    // The inputs that are folders: a DICOM folder (its series) or a Zarr store.
    QAction* openFolder = file->addAction(tr("Open &Folder..."), this, [this] {
        const QString d = QFileDialog::getExistingDirectory(this, tr("Open a DICOM folder or a Zarr store"));
        if (!d.isEmpty()) openInput(d);
    });
    openFolder->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_O));
    file->addAction(tr("Open &Analytic Field..."), this, [this] {
        bool ok = false;
        QStringList names;
        for (const std::string& n : analyticFieldNames()) names << QString::fromStdString(n);
        const QString name = QInputDialog::getItem(this, tr("Analytic field"), tr("Field:"), names, 0, false, &ok);
        if (ok) openInput(QStringLiteral("analytic:%1").arg(name));
    });
    recentMenu_ = file->addMenu(tr("Open &Recent"));
    file->addSeparator();
    file->addAction(tr("Open &Session..."), this, [this] {
        const QString f = QFileDialog::getOpenFileName(this, tr("Open session"), QString(), tr("Sessions (*.json);;All files (*)"));
        if (!f.isEmpty()) openSession(f);
    });
    QAction* save = file->addAction(tr("&Save Session..."), this, [this] {
        const QString f = QFileDialog::getSaveFileName(this, tr("Save session"), QStringLiteral("session.json"), tr("Sessions (*.json)"));
        if (!f.isEmpty()) saveSessionTo(f);
    });
    save->setShortcut(QKeySequence::Save);
    file->addSeparator();
    QAction* exportAct = file->addAction(tr("&Export Figure..."), this, &MainWindow::chooseExport);
    exportAct->setShortcut(Qt::CTRL | Qt::Key_E);
    file->addAction(tr("Copy &Command Line"), this, [this] {
        const QSize s(state_.exportWidth, state_.exportHeight);
        const QString cmd = QStringLiteral("octrace render ") + commandLine(QStringLiteral("figure.png"), s.width(), s.height()).join(' ');
        QApplication::clipboard()->setText(cmd);
        showMessage(cmd);
    });
    file->addSeparator();
    QAction* quit = file->addAction(tr("&Quit"), this, &QWidget::close);
    quit->setShortcut(QKeySequence::Quit);

    QMenu* view = menuBar()->addMenu(tr("&View"));
    QToolBar* bar = addToolBar(tr("View"));
    bar->setObjectName(QStringLiteral("viewToolBar"));
    QAction* reset = view->addAction(tr("&Reset View"), this, [this] {
        state_.cameraSet = false;
        requestRender(false);
    });
    reset->setShortcut(Qt::Key_R);
    bar->addAction(reset);
    const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    for (int i = 0; i < 6; ++i) {
        QAction* a = view->addAction(tr("Look Along %1").arg(names[i]), this, [this, i] { setStandardView(i / 2, i % 2 ? -1 : 1); });
        a->setIconText(names[i]);
        a->setObjectName(QStringLiteral("view") + names[i]);
        bar->addAction(a);
    }
    view->addSeparator();
    bar->addSeparator();
    splitAction_ = view->addAction(tr("&Split View"));
    splitAction_->setCheckable(true);
    splitAction_->setShortcut(Qt::Key_F2);
    connect(splitAction_, &QAction::toggled, this, &MainWindow::setSplit);
    bar->addAction(splitAction_);
    differenceAction_ = view->addAction(tr("&Difference Image"));
    differenceAction_->setCheckable(true);
    differenceAction_->setEnabled(false);
    differenceAction_->setToolTip(tr("Show |left - right| (x4) in the right pane"));
    connect(differenceAction_, &QAction::toggled, this, [this] { requestRender(false); });
    bar->addAction(differenceAction_);
    view->addSeparator();
    const QList<QAction*> layouts = slices_->layoutActions();
    layouts[1]->setShortcut(Qt::Key_F3);
    view->addActions(layouts);
}

QWidget* MainWindow::buildControls() {
    auto* w = new QWidget;
    auto* layout = new QVBoxLayout(w);

    auto* inputBox = new QGroupBox(tr("Input"), w);
    auto* inputForm = new QFormLayout(inputBox);
    inputLabel_ = new QLabel(tr("(none: File > Open, or drop a file here)"), inputBox);
    inputLabel_->setObjectName(QStringLiteral("inputLabel"));
    inputLabel_->setWordWrap(true);
    inputForm->addRow(inputLabel_);
    variableCombo_ = new QComboBox(inputBox);
    variableCombo_->setObjectName(QStringLiteral("variableCombo"));
    variableCombo_->setToolTip(tr("The 3-D variable to draw (NetCDF)"));
    connect(variableCombo_, &QComboBox::activated, this, [this] {
        StudioState s = state_;
        s.variable = variableCombo_->currentText().toStdString();
        s.iso.reset();  // another variable, another range
        load(s);
    });
    inputForm->addRow(tr("Variable"), variableCombo_);
    timeEdit_ = new QLineEdit(inputBox);
    timeEdit_->setObjectName(QStringLiteral("timeEdit"));
    timeEdit_->setPlaceholderText(tr("first step"));
    timeEdit_->setToolTip(tr("Time step of a NetCDF variable with a time axis: an index (0, 1, ...) or a date (1990-07-15)"));
    connect(timeEdit_, &QLineEdit::editingFinished, this, [this] {
        const std::string t = timeEdit_->text().trimmed().toStdString();
        if (t == state_.time) return;
        StudioState s = state_;
        s.time = t;
        load(s);
    });
    inputForm->addRow(tr("Time"), timeEdit_);
    seriesCombo_ = new QComboBox(inputBox);
    seriesCombo_->setObjectName(QStringLiteral("seriesCombo"));
    seriesCombo_->setToolTip(tr("DICOM series (default: the largest)"));
    seriesCombo_->setSizeAdjustPolicy(QComboBox::AdjustToContents);  // its size hint: the longest series named
    connect(seriesCombo_, &QComboBox::activated, this, [this](int index) {
        StudioState s = state_;
        s.series = std::to_string(index + 1);
        s.iso.reset();
        s.cameraSet = false;
        load(s);
    });
    inputForm->addRow(tr("Series"), seriesCombo_);
    layout->addWidget(inputBox);
    buildStepAndOceanControls(inputForm, layout);

    auto* surfBox = new QGroupBox(tr("Surface"), w);
    auto* surfForm = new QFormLayout(surfBox);
    isoSlider_ = new QSlider(Qt::Horizontal, surfBox);
    isoSlider_->setObjectName(QStringLiteral("isoSlider"));
    isoSlider_->setRange(0, kSliderSteps);
    connect(isoSlider_, &QSlider::valueChanged, this, [this](int v) {
        if (updating_) return;
        const InputInfo& in = engine_.info();
        isoEdited(in.minimum + (in.maximum - in.minimum) * v / double(kSliderSteps));
    });
    isoSpin_ = new QDoubleSpinBox(surfBox);
    isoSpin_->setObjectName(QStringLiteral("isoSpin"));
    isoSpin_->setKeyboardTracking(false);
    connect(isoSpin_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (!updating_) isoEdited(v);
    });
    // The CLI's --iso presets (CT, Hounsfield units): on for a field in HU.
    isoPresetCombo_ = new QComboBox(surfBox);
    isoPresetCombo_->setObjectName(QStringLiteral("isoPresetCombo"));
    isoPresetCombo_->setToolTip(tr("CT iso presets in Hounsfield units (a field in HU only)"));
    isoPresetCombo_->addItem(tr("preset"), QString());
    for (const auto& pr : ctIsoPresets())
        isoPresetCombo_->addItem(QStringLiteral("%1 (%2 HU)").arg(QLatin1String(pr.name)).arg(pr.hu), QLatin1String(pr.name));
    isoPresetCombo_->setEnabled(false);
    connect(isoPresetCombo_, &QComboBox::activated, this, [this](int i) {
        if (const auto hu = ctIsoPreset(isoPresetCombo_->itemData(i).toString().toStdString())) isoEdited(*hu);
    });
    auto* isoRow = new QHBoxLayout;
    isoRow->addWidget(isoSpin_, 1);
    isoRow->addWidget(isoPresetCombo_);
    surfForm->addRow(tr("Iso value"), isoSlider_);
    surfForm->addRow(QString(), isoRow);
    rangeLabel_ = new QLabel(surfBox);
    rangeLabel_->setObjectName(QStringLiteral("rangeLabel"));
    surfForm->addRow(tr("Range"), rangeLabel_);
    histogram_ = new HistogramView(surfBox);
    histogram_->setObjectName(QStringLiteral("histogram"));
    connect(histogram_, &HistogramView::isoPicked, this, [this](double v) { isoEdited(v); });
    surfForm->addRow(histogram_);
    depthSpin_ = new QSpinBox(surfBox);
    depthSpin_->setObjectName(QStringLiteral("depthSpin"));
    configure(depthSpin_, model::opt::depth);
    depthSpin_->setValue(state_.depth.value_or(int(model::opt::depth.defaultValue)));
    depthSpin_->setKeyboardTracking(false);
    depthAutoCheck_ = new QCheckBox(tr("auto"), surfBox);
    depthAutoCheck_->setObjectName(QStringLiteral("depthAuto"));
    depthAutoCheck_->setToolTip(QString::fromStdString(model::sayForStudio(model::opt::depth.defaultText)));
    depthAutoCheck_->setChecked(!state_.depth);
    connect(depthSpin_, &QSpinBox::valueChanged, this, [this](int d) {
        if (updating_) return;
        state_.depth = d;  // a depth picked: no longer auto
        updating_ = true;
        depthAutoCheck_->setChecked(false);
        updating_ = false;
        scheduleBuild();
    });
    connect(depthAutoCheck_, &QCheckBox::toggled, this, [this](bool on) {
        if (updating_) return;
        state_.depth = on ? std::nullopt : std::optional<int>(depthSpin_->value());
        scheduleBuild();
    });
    auto* depthRow = new QHBoxLayout;
    depthRow->addWidget(depthSpin_, 1);
    depthRow->addWidget(depthAutoCheck_);
    surfForm->addRow(tr("Depth"), depthRow);
    // `surface` (the options table): auto is the setting unset (smooth, voxel with the papers'
    // renderers), as the CLI without --surface.
    surfaceCombo_ = new QComboBox(surfBox);
    surfaceCombo_->setObjectName(QLatin1String(model::opt::surface.key));
    configure(surfaceCombo_, model::opt::surface);
    surfaceCombo_->addItem(tr("auto"), QString());
    surfaceCombo_->setItemData(0, QString::fromStdString(model::sayForStudio(model::opt::surface.defaultText)), Qt::ToolTipRole);
    for (const std::string& c : model::opt::surface.choiceList())
        surfaceCombo_->addItem(QString::fromStdString(c), QString::fromStdString(c));
    connect(surfaceCombo_, &QComboBox::currentIndexChanged, this, [this] {
        if (!updating_) settingEdited(QLatin1String(model::opt::surface.key), surfaceCombo_->currentData().toString());
    });
    surfForm->addRow(tr(model::opt::surface.label), surfaceCombo_);
    layout->addWidget(surfBox);
    layout->addWidget(buildCutControls(w));

    auto* renderBox = new QGroupBox(tr("Rendering"), w);
    auto* renderForm = new QFormLayout(renderBox);
    rendererCombo_ = new QComboBox(renderBox);
    rendererCombo_->setObjectName(QStringLiteral("rendererCombo"));
    secondCombo_ = new QComboBox(renderBox);
    secondCombo_->setObjectName(QStringLiteral("secondRendererCombo"));
    for (const auto& n : rendererMenuNames()) {
        if (!makeRenderer(resolveRendererName(n).renderer)->drawsVoxels()) continue;
        rendererCombo_->addItem(QString::fromStdString(n));
        secondCombo_->addItem(QString::fromStdString(n));
    }
    rendererCombo_->setCurrentText(QString::fromStdString(state_.renderer));
    secondCombo_->setCurrentText(QString::fromStdString(state_.secondRenderer));
    connect(rendererCombo_, &QComboBox::currentTextChanged, this, [this](const QString& t) {
        state_.renderer = t.toStdString();
        showCoherence();
        requestRender(false);
    });
    secondCombo_->addItem(QString::fromLatin1(kOpenGlPane));
    secondCombo_->setItemData(secondCombo_->count() - 1, tr("The shell's surfels splatted with OpenGL"), Qt::ToolTipRole);
    connect(secondCombo_, &QComboBox::currentTextChanged, this, [this](const QString& t) {
        state_.secondRenderer = t.toStdString();
        differenceAction_->setEnabled(state_.split && state_.secondRenderer != kOpenGlPane);
        showCoherence();
        requestRender(false);
    });
    renderForm->addRow(tr("Renderer"), rendererCombo_);
    renderForm->addRow(tr("Right pane"), secondCombo_);
    // The bound settings of the Rendering panel (coherence), made from the options table and
    // enabled for the renderers that read them.
    addBoundControls(renderForm, renderBox);
    showCoherence();
    fovSpin_ = new QDoubleSpinBox(renderBox);
    fovSpin_->setObjectName(QStringLiteral("fovSpin"));
    configure(fovSpin_, model::opt::fov, 1);
    fovSpin_->setSuffix(QStringLiteral(" deg"));
    fovSpin_->setValue(state_.fov);
    connect(fovSpin_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        state_.fov = v;
        requestRender(false);
    });
    renderForm->addRow(tr(model::opt::fov.label), fovSpin_);
    auto* lightRow = new QHBoxLayout;
    for (int i = 0; i < 3; ++i) {
        lightSpin_[i] = new QDoubleSpinBox(renderBox);
        lightSpin_[i]->setObjectName(QStringLiteral("light%1").arg("xyz"[i]));
        lightSpin_[i]->setRange(-1.0, 1.0);
        lightSpin_[i]->setSingleStep(0.1);
        lightSpin_[i]->setValue(state_.light[i]);
        lightSpin_[i]->setToolTip(tr("Direction towards the light in camera space: x right, y up, z towards the viewer"));
        connect(lightSpin_[i], &QDoubleSpinBox::valueChanged, this, [this, i](double v) {
            state_.light[i] = v;
            if (glm::length(state_.light) > 0.0) requestRender(false);
        });
        lightRow->addWidget(lightSpin_[i]);
    }
    renderForm->addRow(tr("Light"), lightRow);
    ambientSpin_ = new QDoubleSpinBox(renderBox);
    ambientSpin_->setObjectName(QStringLiteral("ambientSpin"));
    configure(ambientSpin_, model::opt::ambient, 2);
    ambientSpin_->setSingleStep(0.05);
    ambientSpin_->setValue(state_.ambient);
    connect(ambientSpin_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (updating_) return;
        state_.ambient = v;
        lightingChanged(state_.lighting == "baked");  // a bake uses it
    });
    renderForm->addRow(tr(model::opt::ambient.label), ambientSpin_);
    lightingCombo_ = new QComboBox(renderBox);
    lightingCombo_->setObjectName(QStringLiteral("lightingCombo"));
    lightingCombo_->addItem(tr("auto (baked if the octree has it)"), QString());
    lightingCombo_->addItem(tr("precomputed (baked)"), QStringLiteral("baked"));
    lightingCombo_->addItem(tr("dynamic"), QStringLiteral("dynamic"));
    lightingCombo_->setToolTip(tr("Precomputed: light, shadows and ambient occlusion baked into the voxels at build time; "
                                  "dynamic: from each voxel's normal and the light direction"));
    connect(lightingCombo_, &QComboBox::currentIndexChanged, this, [this] {
        if (updating_) return;
        state_.lighting = lightingCombo_->currentData().toString().toStdString();
        lightingChanged(true);  // the octree's baked light follows the mode
    });
    renderForm->addRow(tr("Lighting"), lightingCombo_);
    auto* bakeRow = new QHBoxLayout;
    bakeAoSpin_ = new QSpinBox(renderBox);
    bakeAoSpin_->setObjectName(QStringLiteral("bakeAoSpin"));
    configure(bakeAoSpin_, model::opt::bakeAo);
    bakeAoSpin_->setValue(state_.bakeAo);
    bakeAoSpin_->setPrefix(tr("AO rays "));
    bakeAoSpin_->setKeyboardTracking(false);
    connect(bakeAoSpin_, &QSpinBox::valueChanged, this, [this](int v) {
        if (updating_) return;
        state_.bakeAo = v;
        lightingChanged(state_.lighting == "baked");
    });
    bakeShadowsCheck_ = new QCheckBox(tr("shadows"), renderBox);
    bakeShadowsCheck_->setObjectName(QStringLiteral("bakeShadowsCheck"));
    bakeShadowsCheck_->setChecked(state_.bakeShadows);
    configure(bakeShadowsCheck_, model::opt::bakeShadows);
    connect(bakeShadowsCheck_, &QCheckBox::toggled, this, [this](bool on) {
        if (updating_) return;
        state_.bakeShadows = on;
        lightingChanged(state_.lighting == "baked");
    });
    bakeRow->addWidget(bakeAoSpin_);
    bakeRow->addWidget(bakeShadowsCheck_);
    renderForm->addRow(tr("Bake"), bakeRow);
    shadowsCheck_ = new QCheckBox(tr("shadow rays"), renderBox);
    shadowsCheck_->setObjectName(QStringLiteral("shadowsCheck"));
    shadowsCheck_->setChecked(state_.shadows);
    configure(shadowsCheck_, model::opt::shadows);
    connect(shadowsCheck_, &QCheckBox::toggled, this, [this](bool on) {
        if (updating_) return;
        state_.shadows = on;
        lightingChanged(false);
    });
    renderForm->addRow(tr("Dynamic"), shadowsCheck_);
    colormapCombo_ = new QComboBox(renderBox);
    colormapCombo_->setObjectName(QStringLiteral("colormapCombo"));
    colormapCombo_->addItem(tr("(uniform colour)"));
    for (const auto& n : colormapNames()) colormapCombo_->addItem(QString::fromStdString(n));
    colourBar_ = new QLabel(renderBox);
    colourBar_->setObjectName(QStringLiteral("colourBar"));
    connect(colormapCombo_, &QComboBox::currentIndexChanged, this, [this](int i) {
        state_.colormap = i <= 0 ? std::string() : colormapCombo_->currentText().toStdString();
        if (!state_.colormap.empty() && !state_.window.empty() && state_.window != "none") {
            // A colour map and a display window both colour the surface (the CLI refuses both).
            QSignalBlocker block(windowCombo_);
            windowCombo_->setCurrentIndex(0);
            state_.window.clear();
        }
        updateColourBar();
        colouringChanged();
    });
    renderForm->addRow(tr("Colour map"), colormapCombo_);
    renderForm->addRow(tr("low z .. high z"), colourBar_);
    windowCombo_ = new QComboBox(renderBox);
    windowCombo_->setObjectName(QStringLiteral("windowCombo"));
    windowCombo_->setToolTip(tr("Grey the surface by a display window over the value under it (CT presets in HU)"));
    windowCombo_->addItem(tr("(the file's, if any)"), QString());
    windowCombo_->addItem(tr("none"), QStringLiteral("none"));
    for (const auto& p : ctWindowPresets())
        windowCombo_->addItem(QStringLiteral("%1 (%2/%3 HU)").arg(QLatin1String(p.name)).arg(p.window.centre).arg(p.window.width),
                              QLatin1String(p.name));
    connect(windowCombo_, &QComboBox::currentIndexChanged, this, [this] {
        state_.window = windowCombo_->currentData().toString().toStdString();
        if (!state_.window.empty() && state_.window != "none" && !state_.colormap.empty()) {
            QSignalBlocker block(colormapCombo_);
            colormapCombo_->setCurrentIndex(0);
            state_.colormap.clear();
            updateColourBar();
        }
        colouringChanged();
    });
    renderForm->addRow(tr(model::opt::window.label), windowCombo_);
    layout->addWidget(renderBox);
    layout->addStretch(1);
    return w;
}

void MainWindow::colouringChanged() {
    if (updating_) return;
    // The display window is chosen while building (the octree then keeps voxel values): a change
    // of the colouring that changes the window needs a build; otherwise a frame is enough.
    const model::SurfaceSpec a = surfaceArgs(state_);
    const ValueWindow& file = engine_.info().fileWindow;
    const ValueWindow wanted = !state_.window.empty() ? a.window : (!a.colourGiven && a.colormap.empty()) ? file : ValueWindow{};
    const ValueWindow& now = engine_.window();
    if (engine_.hasField() && (wanted.valid() != now.valid() || wanted.centre != now.centre || wanted.width != now.width))
        scheduleBuild();
    else
        requestRender(false);
}

void MainWindow::addBoundControls(QFormLayout* form, QWidget* parent) {
    for (const Binding& b : bindings()) {
        if (!b.renderingControl) continue;
        const Binding* bound = &b;
        QWidget* widget = nullptr;
        std::visit(
            [&](auto m) {
                using Member = decltype(m);
                if constexpr (std::is_same_v<Member, bool StudioState::*>) {
                    auto* check = new QCheckBox(parent);
                    check->setChecked(state_.*m);
                    configure(check, *b.option);
                    connect(check, &QCheckBox::toggled, this, [this, m, bound](bool on) {
                        if (updating_) return;
                        state_.*m = on;
                        boundSettingChanged(*bound);
                    });
                    widget = check;
                } else if constexpr (std::is_same_v<Member, int StudioState::*>) {
                    auto* spin = new QSpinBox(parent);
                    configure(spin, *b.option);
                    spin->setValue(state_.*m);
                    spin->setKeyboardTracking(false);
                    connect(spin, &QSpinBox::valueChanged, this, [this, m, bound](int v) {
                        if (updating_) return;
                        state_.*m = v;
                        boundSettingChanged(*bound);
                    });
                    widget = spin;
                } else {
                    auto* spin = new QDoubleSpinBox(parent);
                    configure(spin, *b.option, 1);
                    spin->setValue(double(state_.*m));
                    spin->setKeyboardTracking(false);
                    connect(spin, &QDoubleSpinBox::valueChanged, this, [this, m, bound](double v) {
                        if (updating_) return;
                        state_.*m = static_cast<std::remove_reference_t<decltype(state_.*m)>>(v);
                        boundSettingChanged(*bound);
                    });
                    widget = spin;
                }
            },
            b.member);
        widget->setObjectName(QString::fromLatin1(b.option->key));
        form->addRow(tr(b.option->label), widget);
        boundControls_.emplace_back(bound, widget);
    }
    showCoherence();
}

void MainWindow::boundSettingChanged(const Binding& b) {
    showCoherence();
    if (b.effect == Binding::Effect::Rebuild) scheduleBuild();
    else requestRender(false);
}

bool MainWindow::flagOn(std::string_view key) const {
    for (const Binding& b : bindings())
        if (key == b.option->key)
            if (const auto* m = std::get_if<bool StudioState::*>(&b.member)) return state_.**m;
    return false;
}

void MainWindow::showCoherence() {
    std::vector<RendererName> names{resolveRendererName(state_.renderer)};
    if (state_.split && state_.secondRenderer != kOpenGlPane) names.push_back(resolveRendererName(state_.secondRenderer));
    std::vector<std::unique_ptr<Renderer>> panes;
    for (const RendererName& n : names) panes.push_back(makeRenderer(n.renderer));
    const auto any = [&panes](bool (Renderer::*has)() const) {
        return std::any_of(panes.begin(), panes.end(), [has](const auto& r) { return ((*r).*has)(); });
    };
    // A pane named X+colour has colour coherence on whatever the check box says.
    const bool named = std::any_of(names.begin(), names.end(), [](const RendererName& n) { return n.colourCoherence; });
    // A bound control is enabled when a pane's renderer reads its setting and the setting it
    // needs (the table's `needs`) is on; a +colour name turns colour coherence on.
    for (const auto& [b, widget] : boundControls_) {
        const model::Option& o = *b->option;
        bool on = !o.renderers || any(o.renderers);
        if (*o.needs) on = on && (flagOn(o.needs) || (named && std::string_view(o.needs) == model::opt::colourCoherence.key));
        widget->setEnabled(on);
    }
}

void MainWindow::lightingChanged(bool rebuild) {
    bakeAoSpin_->setEnabled(state_.lighting == "baked");
    bakeShadowsCheck_->setEnabled(state_.lighting == "baked");
    shadowsCheck_->setEnabled(state_.lighting != "baked");
    if (rebuild) scheduleBuild();
    else requestRender(false);
}

QWidget* MainWindow::buildCutControls(QWidget* parent) {
    auto* box = new QGroupBox(tr("Cut-away (CSG)"), parent);
    auto* form = new QFormLayout(box);
    cutCombo_ = new QComboBox(box);
    cutCombo_->setObjectName(QStringLiteral("cutCombo"));
    cutCombo_->addItem(tr("none"), QString());
    cutCombo_->addItem(tr("box"), QStringLiteral("box"));
    cutCombo_->addItem(tr("sphere"), QStringLiteral("sphere"));
    cutCombo_->addItem(tr("half-space"), QStringLiteral("halfspace"));
    cutCombo_->setToolTip(tr("Cut a solid away from the object (the CLI's --cut); it starts facing the default view"));
    cutEdit_ = new QLineEdit(box);
    cutEdit_->setObjectName(QStringLiteral("cutEdit"));
    cutEdit_->setToolTip(tr("The solid in world units, as --cut takes it: box:X0,Y0,Z0,X1,Y1,Z1, sphere:X,Y,Z,R, "
                            "halfspace:X,Y,Z,NX,NY,NZ, cylinder:X0,Y0,Z0,X1,Y1,Z1,R"));
    clipCheck_ = new QCheckBox(tr("keep only the inside (clip)"), box);
    clipCheck_->setObjectName(QStringLiteral("clipCheck"));
    connect(cutCombo_, &QComboBox::activated, this, [this] {
        const QString kind = cutCombo_->currentData().toString();
        auto tree = engine_.tree();
        setCut(kind.isEmpty() || !tree ? QString() : defaultCut(kind, tree->occupiedBounds()));
    });
    connect(cutEdit_, &QLineEdit::editingFinished, this, [this] {
        if (cutEdit_->text().trimmed().toStdString() != state_.cut) setCut(cutEdit_->text().trimmed());
    });
    connect(clipCheck_, &QCheckBox::toggled, this, [this](bool on) {
        if (updating_) return;
        state_.clip = on;
        if (!state_.cut.empty()) scheduleBuild();
    });
    form->addRow(tr("Solid"), cutCombo_);
    form->addRow(cutEdit_);
    form->addRow(clipCheck_);
    return box;
}

QString MainWindow::defaultCut(const QString& kind, const Box3& b) {
    // Each solid takes away the part of the surface that faces the default view (from the
    // south-east, above: +x, -y, +z).
    const dvec3 c = b.centre(), size = b.hi - b.lo, m = 0.05 * size;
    auto n = [](double v) { return QString::number(v, 'g', 6); };
    if (kind == QLatin1String("box"))
        return QStringLiteral("box:%1,%2,%3,%4,%5,%6").arg(n(c.x), n(b.lo.y - m.y), n(c.z), n(b.hi.x + m.x), n(c.y), n(b.hi.z + m.z));
    if (kind == QLatin1String("sphere"))
        return QStringLiteral("sphere:%1,%2,%3,%4").arg(n(b.hi.x), n(b.lo.y), n(b.hi.z), n(0.5 * glm::length(size)));
    return QStringLiteral("halfspace:%1,%2,%3,%4,%5,%6").arg(n(c.x), n(c.y), n(c.z), n(-1.0), n(1.0), n(-1.0));
}

void MainWindow::setCut(const QString& spec) {
    if (!spec.isEmpty()) {
        try {
            model::checkSolidArgument(spec.toStdString());
        } catch (const std::exception& e) {
            showMessage(QString::fromStdString(model::sayForStudio(e.what())), true);
            cutEdit_->setText(QString::fromStdString(state_.cut));
            return;
        }
    }
    state_.cut = spec.toStdString();
    showCut();
    scheduleBuild();
}

void MainWindow::showCut() {
    QSignalBlocker block(cutCombo_);
    const QString spec = QString::fromStdString(state_.cut);
    cutEdit_->setText(spec);
    const int kind = spec.isEmpty() ? 0 : cutCombo_->findData(spec.section(QLatin1Char(':'), 0, 0));
    cutCombo_->setCurrentIndex(kind < 0 ? 0 : kind);  // a cylinder: shown in the text only
}

void MainWindow::updateColourBar() {
    if (state_.colormap.empty()) {
        colourBar_->clear();
        return;
    }
    QImage bar(200, 12, QImage::Format_RGB32);
    for (int x = 0; x < bar.width(); ++x) {
        const vec3 c = colormap(state_.colormap, float(x) / float(bar.width() - 1));
        const QRgb rgb = qRgb(linearToSrgb8(c.r), linearToSrgb8(c.g), linearToSrgb8(c.b));
        for (int y = 0; y < bar.height(); ++y) bar.setPixel(x, y, rgb);
    }
    colourBar_->setPixmap(QPixmap::fromImage(bar));
}

void MainWindow::showMessage(const QString& text, bool error) {
    messages_->appendPlainText((error ? tr("error: ") : QString()) + text);
    statusLabel_->setText(text);
    if (error) {
        // Not modal for the event loop: the window goes on (and tests are not blocked).
        auto* box = new QMessageBox(QMessageBox::Warning, tr("octrace studio"), text, QMessageBox::Ok, this);
        box->setObjectName(QStringLiteral("errorBox"));
        box->setAttribute(Qt::WA_DeleteOnClose);
        box->open();
    }
}

void MainWindow::openInput(const QString& chosen) {
    // A Zarr store's metadata file (typed or picked in the Open dialog, which picks files, or
    // dropped): the store is read by its folder.
    const std::string store = io::zarrStoreOfMetadataFile(chosen.toStdString());
    const QString input = store.empty() ? chosen : QString::fromStdString(store);
    StudioState s = state_;
    s.input = input.toStdString();
    s.variable.clear();
    s.time.clear();
    s.series.clear();
    s.settings.clear();
    s.iso.reset();
    s.cameraSet = false;
    addRecent(input);
    load(s);
}

void MainWindow::load(const StudioState& s) {
    if (s.input.empty()) return;
    // A build still waiting for its timer was for the input on screen: started after this read,
    // it would supersede it (a newer job), and the input asked for would never come.
    buildTimer_.stop();
    pending_ = s;
    cancelButton_->setEnabled(true);
    engine_.open(s);
}

bool MainWindow::saveSessionTo(const QString& path) {
    try {
        saveSession(state_, path);
    } catch (const std::exception& e) {
        showMessage(QString::fromStdString(model::sayForStudio(e.what())), true);
        return false;
    }
    showMessage(tr("Saved session %1").arg(path));
    return true;
}

bool MainWindow::openSession(const QString& path) {
    StudioState s;
    try {
        s = loadSession(path);
    } catch (const std::exception& e) {
        showMessage(QString::fromStdString(model::sayForStudio(e.what())), true);
        return false;
    }
    state_ = s;
    showState();
    // The layout now; the crosshair, positions and window once the input is read (a session
    // without an input keeps the panes as they are).
    restoreSlices_ = !state_.input.empty();
    slices_->setFourUp(s.fourUp);
    state_.crosshair = s.crosshair;
    state_.sliceAt = s.sliceAt;
    state_.sliceWindow = s.sliceWindow;
    showMessage(tr("Opened session %1").arg(path));
    if (!state_.input.empty()) {
        addRecent(QString::fromStdString(state_.input));
        load(state_);
    }
    return true;
}

void MainWindow::keepSlices() {
    if (restoreSlices_) return;  // a session's panes are still to be shown
    state_.fourUp = slices_->fourUp();
    state_.crosshair.reset();
    state_.sliceAt = {};
    if (engine_.field()) {
        state_.crosshair = slices_->cursor();
        for (int i = 0; i < 3; ++i) state_.sliceAt[std::size_t(i)] = slices_->at(i);
    }
    state_.sliceWindow = slices_->windowText();
}

void MainWindow::showState() {
    updating_ = true;
    if (state_.depth) depthSpin_->setValue(*state_.depth);
    depthAutoCheck_->setChecked(!state_.depth);
    rendererCombo_->setCurrentText(QString::fromStdString(state_.renderer));
    secondCombo_->setCurrentText(QString::fromStdString(state_.secondRenderer));
    const auto surface = state_.settings.find(model::opt::surface.key);
    surfaceCombo_->setCurrentIndex(std::max(
        0, surfaceCombo_->findData(surface == state_.settings.end() ? QString() : QString::fromStdString(surface->second))));
    fovSpin_->setValue(state_.fov);
    for (int i = 0; i < 3; ++i) lightSpin_[i]->setValue(state_.light[i]);
    ambientSpin_->setValue(state_.ambient);
    lightingCombo_->setCurrentIndex(std::max(0, lightingCombo_->findData(QString::fromStdString(state_.lighting))));
    bakeAoSpin_->setValue(state_.bakeAo);
    bakeShadowsCheck_->setChecked(state_.bakeShadows);
    shadowsCheck_->setChecked(state_.shadows);
    for (const auto& [b, widget] : boundControls_) {
        QWidget* w = widget;
        std::visit(
            [&](auto m) {
                if constexpr (std::is_same_v<decltype(m), bool StudioState::*>) static_cast<QCheckBox*>(w)->setChecked(state_.*m);
                else if constexpr (std::is_same_v<decltype(m), int StudioState::*>) static_cast<QSpinBox*>(w)->setValue(state_.*m);
                else static_cast<QDoubleSpinBox*>(w)->setValue(double(state_.*m));
            },
            b->member);
    }
    showCoherence();
    clipCheck_->setChecked(state_.clip);
    showCut();
    colormapCombo_->setCurrentIndex(state_.colormap.empty() ? 0 : colormapCombo_->findText(QString::fromStdString(state_.colormap)));
    windowCombo_->setCurrentIndex(std::max(0, windowCombo_->findData(QString::fromStdString(state_.window))));
    timeEdit_->setText(QString::fromStdString(state_.time));
    splitAction_->setChecked(state_.split);
    updating_ = false;
    setSplit(state_.split);
    updateColourBar();
    bakeAoSpin_->setEnabled(state_.lighting == "baked");
    bakeShadowsCheck_->setEnabled(state_.lighting == "baked");
    shadowsCheck_->setEnabled(state_.lighting != "baked");
}

void MainWindow::addRecent(const QString& input) {
    QSettings settings;
    QStringList list = settings.value(kRecentKey).toStringList();
    const QString abs = input.startsWith(QStringLiteral("analytic:")) ? input : QFileInfo(input).absoluteFilePath();
    list.removeAll(abs);
    list.prepend(abs);
    while (list.size() > kMaxRecent) list.removeLast();
    settings.setValue(kRecentKey, list);
    updateRecentMenu();
}

void MainWindow::updateRecentMenu() {
    recentMenu_->clear();
    const QStringList list = QSettings().value(kRecentKey).toStringList();
    for (const QString& f : list) recentMenu_->addAction(f, this, [this, f] { openInput(f); });
    recentMenu_->setEnabled(!list.isEmpty());
}

void MainWindow::chooseOpen() {
    const QString f = QFileDialog::getOpenFileName(
        this, tr("Open input"), QString(),
        tr("Volumes (*.nc *.cdf *.nc4 *.nrrd *.nhdr *.dcm *.mhd *.mha *.nii *.nii.gz *.hdr *.vti *.oct DICOMDIR);;All files (*)"));
    if (!f.isEmpty()) openInput(f);
}

void MainWindow::dragEnterEvent(QDragEnterEvent* e) {
    if (e->mimeData()->hasUrls()) e->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* e) {
    const QList<QUrl> urls = e->mimeData()->urls();
    if (!urls.isEmpty() && urls.first().isLocalFile()) openInput(urls.first().toLocalFile());
}

void MainWindow::onInputLoaded() {
    // The input read is now the state's; until then a failed read left the state alone.
    state_.input = pending_.input;
    state_.variable = pending_.variable;
    if (state_.variable.empty()) state_.variable = engine_.info().variableChosen.toStdString();
    state_.time = pending_.time;
    state_.series = pending_.series;
    state_.settings = pending_.settings;
    state_.iso = pending_.iso;
    state_.cameraSet = pending_.cameraSet;
    state_.position = pending_.position;
    state_.lookAt = pending_.lookAt;
    state_.up = pending_.up;
    // The file's (or DICOM folder's) name, as the title; the path as given in the tooltip.
    const QString input = QString::fromStdString(state_.input);
    const QString name = QFileInfo(input).fileName().isEmpty() ? input : QFileInfo(input).fileName();
    inputLabel_->setText(name);
    inputLabel_->setToolTip(input);
    setWindowTitle(tr("%1 - octrace studio").arg(name));
    const InputInfo& in = engine_.info();
    updating_ = true;
    variableCombo_->clear();
    variableCombo_->addItems(in.variables.isEmpty() ? QStringList{in.variable} : in.variables);
    variableCombo_->setCurrentText(in.variable);
    variableCombo_->setEnabled(in.variables.size() > 1);
    seriesCombo_->clear();
    seriesCombo_->addItems(in.series);
    // As wide as the longest series' name (the side panel widens with it), up to 60 characters.
    seriesCombo_->setMinimumWidth(std::min(seriesCombo_->sizeHint().width(), 60 * seriesCombo_->fontMetrics().averageCharWidth()));
    seriesCombo_->setCurrentIndex(in.seriesRead);  // the series on screen, not the first listed
    seriesCombo_->setEnabled(in.series.size() > 1);
    timeEdit_->setEnabled(!in.octreeFile);
    const double span = in.maximum - in.minimum;
    const int decimals = span > 0.0 ? std::clamp(3 - int(std::floor(std::log10(span))), 0, 8) : 3;
    isoSpin_->setDecimals(decimals);
    isoSpin_->setRange(in.minimum, in.maximum);
    isoSpin_->setSingleStep(span > 0.0 ? span / 100.0 : 1.0);
    isoSpin_->setSuffix(in.units.isEmpty() ? QString() : QStringLiteral(" ") + in.units);
    isoSpin_->setEnabled(!in.octreeFile);
    isoSlider_->setEnabled(!in.octreeFile);
    isoPresetCombo_->setEnabled(!in.octreeFile && in.units == QLatin1String("HU"));
    if (auto* model = qobject_cast<QStandardItemModel*>(isoPresetCombo_->model()))
        for (int i = 1; i < isoPresetCombo_->count(); ++i) {
            // A preset outside the values read would find no surface (the CLI refuses it too).
            const double hu = *ctIsoPreset(isoPresetCombo_->itemData(i).toString().toStdString());
            const bool inside = hu >= in.minimum && hu <= in.maximum;
            model->item(i)->setEnabled(inside);
            model->item(i)->setToolTip(inside ? QString() : tr("outside the values read, %1 .. %2 HU").arg(in.minimum).arg(in.maximum));
        }
    depthSpin_->setEnabled(!in.octreeFile);
    depthAutoCheck_->setEnabled(!in.octreeFile);
    rangeLabel_->setText(in.octreeFile ? tr("fixed by the octree file")
                                       : QStringLiteral("%1 .. %2 %3").arg(in.minimum).arg(in.maximum).arg(in.units));
    histogram_->setHistogram(in.histogram, in.minimum, in.maximum);
    updating_ = false;
    showStepsAndOcean();
    showMessage(tr("Read %1: %2 [%3 .. %4] %5").arg(in.input, in.variable).arg(in.minimum).arg(in.maximum).arg(in.units));
    if (restoreSlices_) {
        // The session's crosshair, slice positions and window, on the field it names.
        restoreSlices_ = false;
        const StudioState saved = state_;
        if (saved.crosshair) slices_->setCursor(*saved.crosshair);
        for (int i = 0; i < 3; ++i)
            if (const auto& at = saved.sliceAt[std::size_t(i)]) slices_->setAt(i, *at);
        if (!slices_->setWindowText(saved.sliceWindow))
            showMessage(tr("The session's slice window %1 does not apply to %2: the automatic window")
                            .arg(QString::fromStdString(saved.sliceWindow), in.input));
        keepSlices();
    }
}

void MainWindow::onSurfaceBuilt() {
    progress_->hide();
    cancelButton_->setEnabled(false);
    state_.iso = engine_.iso();
    setIsoControls(engine_.iso());
    showBuiltDepth();
    const auto tree = engine_.tree();
    showMessage(tr("Surface at %1: %2 boundary voxels at depth %3")
                    .arg(engine_.iso())
                    .arg(tree->boundaryVoxels())
                    .arg(tree->depth));
    requestRender(false);
}

void MainWindow::showBuiltDepth() {
    state_.depth = engine_.depthSetting();
    updating_ = true;
    depthSpin_->setValue(engine_.depth());
    depthAutoCheck_->setChecked(!state_.depth);
    updating_ = false;
}

void MainWindow::setIsoControls(double iso) {
    const InputInfo& in = engine_.info();
    updating_ = true;
    isoSpin_->setValue(iso);
    if (in.maximum > in.minimum) isoSlider_->setValue(int(std::lround((iso - in.minimum) / (in.maximum - in.minimum) * kSliderSteps)));
    histogram_->setIso(iso);
    updating_ = false;
}

void MainWindow::isoEdited(double iso) {
    state_.iso = iso;
    setIsoControls(iso);
    scheduleBuild();
}

void MainWindow::scheduleBuild() {
    if (engine_.hasField() || engine_.tree()) buildTimer_.start();
}

QSize MainWindow::paneSize() const { return views_[0]->size() * views_[0]->devicePixelRatio(); }

Camera MainWindow::viewCamera() const {
    const QSize s = paneSize();
    auto tree = engine_.tree();
    return cameraFor(state_, tree ? tree->occupiedBounds() : Box3{dvec3(-1.0), dvec3(1.0)}, engine_.view(), std::max(1, s.width()),
                     std::max(1, s.height()));
}

void MainWindow::cameraMoved(const Camera& c) {
    storeCamera(state_, c);
    requestRender(true);
    exactTimer_.start();
}

void MainWindow::setStandardView(int axis, int sign) {
    auto tree = engine_.tree();
    if (!tree) return;
    const QSize s = paneSize();
    storeCamera(state_, standardView(tree->occupiedBounds(), axis, sign, std::max(1, s.width()), std::max(1, s.height()),
                                     state_.fov));
    requestRender(false);
}

void MainWindow::setSplit(bool on) {
    state_.split = on;
    secondPane_->setVisible(on);
    differenceAction_->setEnabled(on && state_.secondRenderer != kOpenGlPane);
    showCoherence();
    exactTimer_.start();
}

bool MainWindow::openGlPane() const { return state_.split && state_.secondRenderer == kOpenGlPane; }

SurfelView* MainWindow::surfelView() {
    if (!surfelView_) {
        surfelView_ = new SurfelView(secondPane_);
        surfelView_->setObjectName(QStringLiteral("surfelView"));
        connectNavigation(surfelView_->input());
        secondPane_->addWidget(surfelView_);
    }
    return surfelView_;
}

void MainWindow::updateSurfelView() {
    auto tree = engine_.tree();
    if (!tree || !openGlPane()) return;
    const RenderSettings rs = engine_.settingsFor(state_, false);
    if (tree != surfelTree_ || rs.colour != surfelSettings_.colour || rs.colormap != surfelSettings_.colormap) {
        surfels_ = std::make_shared<const std::vector<Surfel>>(extractSurfels(*tree, rs));
        surfelTree_ = tree;
        surfelSettings_ = rs;
        surfelView()->setSurfels(surfels_);
    }
    SurfelView* gl = surfelView();
    const qreal dpr = gl->devicePixelRatioF();
    gl->setView(cameraFor(state_, tree->occupiedBounds(), engine_.view(), std::max(1, int(gl->width() * dpr)),
                          std::max(1, int(gl->height() * dpr))),
                         rs);
}

void MainWindow::requestRender(bool preview) {
    if (!engine_.tree()) return;
    FrameRequest r;
    r.renderers = {state_.renderer};
    if (state_.split && !openGlPane()) r.renderers.push_back(state_.secondRenderer);
    secondPane_->setCurrentWidget(openGlPane() ? static_cast<QWidget*>(surfelView()) : views_[1]);
    if (openGlPane()) updateSurfelView();
    r.camera = viewCamera();
    try {
        r.camera.validate();
    } catch (const std::exception& e) {
        showMessage(QString::fromStdString(model::sayForStudio(e.what())), true);
        return;
    }
    r.settings = engine_.settingsFor(state_, false);
    r.preview = preview;
    r.difference = state_.split && differenceAction_->isChecked();
    r.inputSerial = latency_.latest();
    engine_.requestFrame(r);
}

void MainWindow::onFrame(const FrameResult& r) {
    for (std::size_t i = 0; i < r.panes.size() && i < 2; ++i) {
        QString text = statsText(r.panes[i], r.fullMs, r.preview, r.level);
        if (r.panes.size() == 2 && !r.preview) text += tr("\n%1 mismatching pixels").arg(r.mismatching);
        views_[i]->setImage(i == 1 && !r.difference.isNull() ? r.difference : r.panes[i].image, i == 0 ? r.inputSerial : 0);
        views_[i]->setOverlay(i == 1 && !r.difference.isNull() ? tr("difference |left - right| x4\n") + text : text);
    }
    shownPreview_ = r.preview;
    showCrosshair();
    if (!r.preview && stepPending_ && !engine_.building()) {
        stepPending_ = false;
        stepSlider_->stepShown();  // playing: the next step follows
    }
    if (!r.preview) emit frameShown();
}

void MainWindow::framePainted(std::uint64_t serial) {
    const auto ms = latency_.painted(serial, shownPreview_);
    if (!ms) return;
    latencyLabel_->setText(tr("input to paint %1 ms%2").arg(*ms, 0, 'f', 0).arg(shownPreview_ ? tr(" (preview)") : QString()));
    emit inputAnswered(*ms, shownPreview_);
}

void MainWindow::showCrosshair() {
    std::optional<QPointF> at;
    if (slices_->fourUp())
        if (const auto px = slices_->crosshairIn(viewCamera())) at = *px / views_[0]->devicePixelRatioF();
    views_[0]->setMarker(at);
}

QStringList MainWindow::commandLine(const QString& output, int width, int height) const {
    auto tree = engine_.tree();
    StudioState s = state_;
    // `depth` auto: the depth it chose for the surface shown (a city's or a sphere scene's
    // depends on the view's size, which the studio's build takes from the table's default).
    if (!s.depth && tree) s.depth = engine_.depth();
    const Box3 bounds = tree ? tree->occupiedBounds() : Box3{dvec3(-1.0), dvec3(1.0)};
    Camera cam;
    try {
        if (tree) cam = engine_.exportView(s, width, height).camera;  // the export's, its figure fitted to its text
        else cam = cameraFor(s, bounds, engine_.view(), width, height);
    } catch (const UsageError&) {
        cam = cameraFor(s, bounds, engine_.view(), width, height);  // a figure too small for its text: the CLI says so too
    }
    QStringList out;
    for (const auto& a : renderArguments(s, cam, engine_.iso(), output.toStdString(), width, height)) out << QString::fromStdString(a);
    return out;
}

void MainWindow::exportFigure(const QString& path, int width, int height, bool transparent) {
    StudioState s = state_;
    s.transparent = transparent;
    engine_.exportFigure(s, path, width, height);  // refuses a size out of range
    if (width < 1 || height < 1 || width > kMaxExportSide || height > kMaxExportSide) return;
    state_.exportWidth = width;  // the next export's defaults
    state_.exportHeight = height;
    state_.transparent = transparent;
}

void MainWindow::setFigure(bool figure, const QString& title, int dpi, bool scaleBar) {
    state_.figure = figure;
    state_.title = title.toStdString();
    state_.dpi = std::clamp(dpi, 36, 1200);
    state_.scaleBar = scaleBar;
}

int scaledDpi(int dpi, int fromWidth, int toWidth) {
    if (fromWidth < 1 || toWidth < 1) return dpi;
    return std::clamp(int(std::lround(double(dpi) * double(toWidth) / double(fromWidth))), 36, 1200);
}

void MainWindow::chooseExport() {
    QDialog dlg(this);
    dlg.setObjectName(QStringLiteral("exportDialog"));
    dlg.setWindowTitle(tr("Export figure"));
    auto* form = new QFormLayout(&dlg);
    auto* path = new QLineEdit(&dlg);
    path->setObjectName(QStringLiteral("exportPath"));
    path->setText(exportPath_);  // the last export's file (and folder), for this run of the studio
    auto* browse = new QPushButton(tr("Browse..."), &dlg);
    connect(browse, &QPushButton::clicked, &dlg, [&] {
        const QString f = QFileDialog::getSaveFileName(&dlg, tr("Export figure"), path->text(),
                                                       tr("Images (*.png *.exr *.tif *.tiff)"));
        if (!f.isEmpty()) path->setText(f);
    });
    auto* row = new QHBoxLayout;
    row->addWidget(path);
    row->addWidget(browse);
    form->addRow(tr("File (.png, .exr, .tif)"), row);
    auto* w = new QSpinBox(&dlg);
    auto* h = new QSpinBox(&dlg);
    configure(w, model::opt::width);
    configure(h, model::opt::height);
    for (QSpinBox* s : {w, h}) {
        s->setSuffix(QStringLiteral(" px"));
        s->setKeyboardTracking(false);  // a value while typing (1, 10, 100 on the way to 1000) is none
    }
    w->setObjectName(QStringLiteral("exportWidth"));
    h->setObjectName(QStringLiteral("exportHeight"));
    w->setValue(state_.exportWidth);
    h->setValue(state_.exportHeight);
    form->addRow(tr("Width"), w);
    form->addRow(tr("Height"), h);
    auto* transparent = new QCheckBox(tr("Transparent background"), &dlg);
    transparent->setObjectName(QStringLiteral("exportTransparent"));
    transparent->setChecked(state_.transparent);
    form->addRow(transparent);
    // A publication figure, as render --figure: the text is set in points at the dpi. The dpi
    // follows the width (text, lines and bars keep their share of the figure: the annotations
    // scale with the image), always in proportion to the width and dpi the dialog opened with
    // or the user last set the dpi at: never from a value it scaled itself, so that no change
    // of width, however many, builds on the rounding or the 36..1200 clamp of an earlier one.
    auto* figure = new QGroupBox(tr("Figure (PNG): title, colour bar, box with ticks"), &dlg);
    figure->setObjectName(QStringLiteral("figureBox"));
    figure->setCheckable(true);
    figure->setChecked(state_.figure);
    auto* figureForm = new QFormLayout(figure);
    auto* title = new QLineEdit(QString::fromStdString(state_.title), figure);
    title->setObjectName(QStringLiteral("figureTitle"));
    figureForm->addRow(tr("Title"), title);
    auto* dpi = new QSpinBox(figure);
    dpi->setObjectName(QStringLiteral("figureDpi"));
    configure(dpi, model::opt::dpi);
    dpi->setValue(state_.dpi);
    dpi->setSuffix(tr(" dpi"));
    dpi->setKeyboardTracking(false);
    struct {
        int width, dpi;
        bool scaling = false;
    } base{w->value(), dpi->value()};
    connect(w, &QSpinBox::valueChanged, dpi, [dpi, &base](int width) {
        base.scaling = true;
        dpi->setValue(scaledDpi(base.dpi, base.width, width));
        base.scaling = false;
    });
    connect(dpi, &QSpinBox::valueChanged, w, [w, &base](int value) {
        if (!base.scaling) base = {w->value(), value};  // set by hand: the new reference
    });
    figureForm->addRow(tr("Resolution"), dpi);
    auto* scaleBar = new QCheckBox(tr("Scale bar"), figure);
    scaleBar->setObjectName(QStringLiteral("figureScaleBar"));
    scaleBar->setChecked(state_.scaleBar);
    figureForm->addRow(scaleBar);
    figureForm->addRow(new QLabel(state_.colormap.empty() ? tr("Colour bar: choose a colour map") : tr("Colour bar: %1").arg(QString::fromStdString(state_.colormap)), figure));
    form->addRow(figure);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, &dlg);
    connect(buttons, &QDialogButtonBox::accepted, &dlg, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dlg, &QDialog::reject);
    form->addRow(buttons);
    if (dlg.exec() != QDialog::Accepted) return;
    setFigure(figure->isChecked(), title->text(), dpi->value(), scaleBar->isChecked());
    exportFigure(path->text(), w->value(), h->value(), transparent->isChecked());
    if (!path->text().trimmed().isEmpty()) exportPath_ = QFileInfo(path->text().trimmed()).absoluteFilePath();
}

}  // namespace octrace::studio
