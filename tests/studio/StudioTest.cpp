// QTest of octrace-studio driving the real window under Xvfb (ctest runs it through
// xvfb-run -a): open a sample, change the iso value, switch renderers, move the camera, cancel a
// build, export figures — and check that an exported PNG has the same pixels as the CLI's
// `octrace render` of the same state (the command line the studio itself gives).
// With OCTRACE_STUDIO_SCREENSHOTS=DIR set, screenshots of the window go to DIR (the images of
// docs/user/studio.md: scripts/studio-screenshots.sh).
#include "Engine.h"
#include "MainWindow.h"

#include "octrace/render/Renderer.h"
#include "RenderView.h"
#include "Session.h"
#include "Navigation.h"
#include "SidePanel.h"
#include "SliceViews.h"
#include "SurfelView.h"

#include "OptionWidgets.h"
#include "octrace/model/OptionTable.h"
#include "octrace/model/Surface.h"
#include "octrace/io/DicomSeriesWriter.h"
#include "octrace/io/FieldReader.h"
#include "octrace/util/Error.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDockWidget>
#include <QGroupBox>
#include <QTimer>
#include <QToolButton>
#include <QDoubleSpinBox>
#include <QImage>
#include <QLineEdit>
#include <QLabel>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QStatusBar>
#include <QProcess>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSpontaneKeyEvent>
#include <QWheelEvent>
#include <QSignalSpy>
#include <QSpinBox>
#include <QStandardItemModel>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <functional>

#include "StudioTestSupport.h"

using octrace::studio::Engine;
using octrace::studio::FrameResult;
using octrace::studio::MainWindow;
using octrace::studio::RenderView;

using namespace octrace::studio::test;

class StudioTest : public QObject {
    Q_OBJECT
private:
    MainWindow* window_ = nullptr;
    QTemporaryDir tmp_;
    QString screenshots_;

    void screenshot(const QString& name) {
        if (!screenshots_.isEmpty()) QVERIFY(saveScreenshot(window_, tmp_.path(), screenshots_ + QLatin1Char('/') + name));
    }
    /// Waits for the next exact frame on screen.
    void waitFrame() {
        QSignalSpy frames(window_, &MainWindow::frameShown);
        QVERIFY(frames.wait(kWaitMs));
    }
    /// Exports at width x height, then renders the studio's own command line with the CLI and
    /// compares the two PNG files pixel by pixel.
    void exportEqualsCli(const QString& stem, int width, int height, bool transparent) {
        const QString studioPng = tmp_.filePath(stem + QStringLiteral("-studio.png"));
        const QString cliPng = tmp_.filePath(stem + QStringLiteral("-cli.png"));
        QSignalSpy exported(&window_->engine(), &Engine::exported);
        window_->exportFigure(studioPng, width, height, transparent);
        QVERIFY(exported.wait(kWaitMs));
        QCOMPARE(QImage(studioPng).size(), QSize(width, height));
        QCOMPARE(runCli(window_->commandLine(cliPng, width, height)), 0);
        QCOMPARE(differingPixels(studioPng, cliPng), 0);
        QImage img(studioPng);
        QVERIFY(surfacePixels(img, img.pixel(0, 0)) > width * height / 50);  // the surface is in the picture
        QCOMPARE(img.hasAlphaChannel(), transparent);
        if (transparent) QCOMPARE(qAlpha(img.pixel(0, 0)), 0);
    }

    /// The export dialog's controls (null where one is missing).
    struct ExportControls {
        QLineEdit* path = nullptr;
        QSpinBox *width = nullptr, *height = nullptr, *dpi = nullptr;
        QGroupBox* figure = nullptr;
        QLineEdit* title = nullptr;
        QCheckBox* scaleBar = nullptr;
        bool complete() const { return path && width && height && dpi && figure && title && scaleBar; }
    };
    static ExportControls exportControls(QDialog* dlg) {
        return {dlg->findChild<QLineEdit*>(QStringLiteral("exportPath")), dlg->findChild<QSpinBox*>(QStringLiteral("exportWidth")),
                dlg->findChild<QSpinBox*>(QStringLiteral("exportHeight")), dlg->findChild<QSpinBox*>(QStringLiteral("figureDpi")),
                dlg->findChild<QGroupBox*>(QStringLiteral("figureBox")), dlg->findChild<QLineEdit*>(QStringLiteral("figureTitle")),
                dlg->findChild<QCheckBox*>(QStringLiteral("figureScaleBar"))};
    }
    /// Opens File > Export Figure... and hands the dialog to `fill` (which accepts or rejects
    /// it; a dialog left open is rejected); returns whether the dialog opened.
    bool runExportDialog(const std::function<void(QDialog*)>& fill) {
        QAction* action = nullptr;
        for (QAction* a : window_->findChildren<QAction*>())
            if (a->text() == QStringLiteral("&Export Figure...")) action = a;
        if (!action) return false;
        // A message box left open (window-modal) would be the active modal widget, not the dialog.
        for (auto* box : window_->findChildren<QWidget*>(QStringLiteral("errorBox"))) box->close();
        bool opened = false;
        QTimer poll;
        poll.setInterval(20);
        connect(&poll, &QTimer::timeout, this, [&] {
            auto* dlg = qobject_cast<QDialog*>(QApplication::activeModalWidget());
            if (!dlg || dlg->objectName() != QStringLiteral("exportDialog")) return;
            poll.stop();
            opened = true;
            fill(dlg);
            if (dlg->isVisible()) dlg->reject();
        });
        poll.start();
        action->trigger();  // returns when the dialog has closed
        return opened;
    }
    /// Opens the torus sample as a user of the repository types it, from the samples' parent
    /// folder (so the window and its screenshots show that path), unless it is the surface on
    /// screen already: a test that needs a surface opens it itself, whatever ran before it.
    void openSample() {
        QVERIFY(QDir::setCurrent(QStringLiteral(OCTRACE_SAMPLES "/..")));
        const QString sample = QStringLiteral("data_samples/torus.nrrd");
        if (window_->state().input == sample.toStdString() && window_->engine().surface()) return;
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        window_->openInput(sample);
        QVERIFY(built.wait(kWaitMs));
        waitFrame();
    }
    QString messagesText() const {
        auto* messages = window_->findChild<QDockWidget*>(QStringLiteral("messagesDock"))->findChild<QPlainTextEdit*>();
        return messages ? messages->toPlainText() : QString();
    }
    /// The side panel (the dock's scroll area) and the controls in it that take the wheel.
    QScrollArea* sidePanel() const { return window_->findChild<QScrollArea*>(QStringLiteral("sidePanel")); }
    QList<QWidget*> wheelControls() const {
        QList<QWidget*> out;
        for (QWidget* w : sidePanel()->widget()->findChildren<QWidget*>())
            if (octrace::studio::SidePanel::isWheelControl(w) && w->isVisible()) out << w;
        return out;
    }
    /// A control's value as text (spin box, combo box, slider).
    static QString controlValue(QWidget* w) {
        if (auto* spin = qobject_cast<QAbstractSpinBox*>(w)) return spin->text();
        if (auto* combo = qobject_cast<QComboBox*>(w)) return QString::number(combo->currentIndex());
        if (auto* slider = qobject_cast<QAbstractSlider*>(w)) return QString::number(slider->value());
        return QString();
    }
    /// A turn of the mouse wheel over the middle of `w`, delivered as the window system's
    /// (spontaneous: Qt passes an ignored one on to the parents, as it does a real one).
    static void wheel(QWidget* w, int angle) {
        // To the widget under the pointer, as the window delivers it: a spin box's line edit.
        const QPoint centre(w->width() / 2, w->height() / 2);
        QWidget* under = w->childAt(centre) ? w->childAt(centre) : w;
        const QPointF local = under->mapFrom(w, QPointF(centre));
        QWheelEvent e(local, under->mapToGlobal(local), QPoint(), QPoint(0, angle), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
        QSpontaneKeyEvent::setSpontaneous(&e);
        QApplication::instance()->notify(under, &e);
    }

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);  // recent files in a test location
        QVERIFY(tmp_.isValid());
        screenshots_ = qEnvironmentVariable("OCTRACE_STUDIO_SCREENSHOTS");
        window_ = new MainWindow;
        window_->resize(1000, 640);
        window_->show();
        QVERIFY(QTest::qWaitForWindowExposed(window_));
    }

    void framePoolGivesBackAFrameOfTheAskedSizeWithinItsLimits() {
        using octrace::Frame;
        using octrace::studio::FramePool;
        FramePool pool;
        QCOMPARE(pool.take(64, 32).width, 0);  // nothing kept: an empty frame
        Frame a(64, 32);
        const auto* buffer = a.rgba.data();
        pool.give(std::move(a));
        QCOMPARE(pool.take(32, 64).width, 0);  // another size
        Frame b = pool.take(64, 32);
        QCOMPARE(b.width, 64);
        QCOMPARE(b.height, 32);
        QVERIFY(b.rgba.data() == buffer);  // the same buffers: the renderer's reshape keeps them
        QCOMPARE(pool.take(64, 32).width, 0);  // handed out once
        // At most kPerSize of a size, the newest kept.
        std::vector<const octrace::vec4*> given;
        for (std::size_t i = 0; i < FramePool::kPerSize + 2; ++i) {
            Frame f(16, 16);
            given.push_back(f.rgba.data());
            pool.give(std::move(f));
        }
        for (std::size_t i = 0; i < FramePool::kPerSize; ++i) {
            const Frame f = pool.take(16, 16);
            QCOMPARE(f.width, 16);
            QVERIFY(std::find(given.end() - std::ptrdiff_t(FramePool::kPerSize), given.end(), f.rgba.data()) != given.end());
        }
        QCOMPARE(pool.take(16, 16).width, 0);
        // Within kKeepBytes in all: a frame larger than the budget is not kept and drops nothing;
        // one that fits drops the oldest until the budget holds.
        int side = 1;
        while (Frame::bytesFor(side, side) <= FramePool::kKeepBytes) side *= 2;
        pool.give(Frame(8, 8));
        Frame big;
        big.width = big.height = side;  // only the size counts (no buffers allocated)
        pool.give(std::move(big));
        QCOMPARE(pool.take(side, side).width, 0);
        QCOMPARE(pool.take(8, 8).width, 8);
        pool.give(Frame(8, 8));
        Frame half;
        half.width = half.height = side / 2;  // a quarter of the smallest square over budget, which fits;
        while (Frame::bytesFor(half.width, half.height) * 2 <= FramePool::kKeepBytes) half.width *= 2;  // two must not
        const int halfWidth = half.width;
        pool.give(std::move(half));
        QCOMPARE(pool.take(8, 8).width, 8);  // both fit
        pool.give(Frame(8, 8));
        Frame second;
        second.width = halfWidth + 1;
        second.height = side / 2;
        pool.give(std::move(second));  // the first and the second are over budget: the oldest, the first, goes
        QCOMPARE(pool.take(halfWidth, side / 2).width, 0);
        QCOMPARE(pool.take(8, 8).width, 8);
        QCOMPARE(pool.take(halfWidth + 1, side / 2).width, halfWidth + 1);
    }

    void opensSample() {
        openSample();
        const auto& info = window_->engine().info();
        QVERIFY(info.maximum > info.minimum);
        // The CLI's default: Otsu's threshold of an image volume (the NRRD sample) by the model.
        QCOMPARE(window_->engine().iso(), octrace::model::defaultIso(*window_->engine().field(), window_->state().input).first);
        QVERIFY(window_->engine().tree()->boundaryVoxels() > 0);
        const QImage shown = window_->view(0)->image();
        QCOMPARE(shown.size(), window_->view(0)->size());
        QVERIFY(surfacePixels(shown, shown.pixel(0, 0)) > 1000);
        screenshot(QStringLiteral("studio-main.png"));
    }

    void isoPresetsNeedHounsfieldUnits() {
        auto* presets = window_->findChild<QComboBox*>(QStringLiteral("isoPresetCombo"));
        QVERIFY(presets);
        QVERIFY(!presets->isEnabled());  // the torus has no units
        QCOMPARE(presets->count(), 3);   // (preset), skin, bone: the CLI's --iso names
    }

    void changesIsoValue() {
        auto* spin = window_->findChild<QDoubleSpinBox*>(QStringLiteral("isoSpin"));
        QVERIFY(spin);
        const auto& info = window_->engine().info();
        const std::size_t before = window_->engine().tree()->boundaryVoxels();
        const double iso = info.minimum + 0.3 * (info.maximum - info.minimum);
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        spin->setValue(iso);
        QVERIFY(built.wait(kWaitMs));
        QVERIFY(std::abs(window_->engine().iso() - spin->value()) < 1e-12);
        QVERIFY(window_->state().iso.has_value());
        QVERIFY(window_->engine().tree()->boundaryVoxels() != before);
        waitFrame();
    }

    void changesDepth() {
        auto* depth = window_->findChild<QSpinBox*>(QStringLiteral("depthSpin"));
        auto* automatic = window_->findChild<QCheckBox*>(QStringLiteral("depthAuto"));
        QVERIFY(depth && automatic);
        // Opened with `depth` auto, render's default: the box shows the depth it chose.
        QVERIFY(automatic->isChecked());
        QVERIFY(!window_->state().depth);
        const int chosen = window_->engine().depth();
        QCOMPARE(depth->value(), chosen);
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        const int other = chosen == 7 ? 6 : 7;
        depth->setValue(other);
        QVERIFY(built.wait(kWaitMs));
        QCOMPARE(window_->engine().tree()->depth, other);
        QCOMPARE(window_->state().depth, std::optional<int>(other));
        QVERIFY(!automatic->isChecked());
        // Back to auto: the same depth as at first.
        automatic->setChecked(true);
        QVERIFY(built.wait(kWaitMs));
        QCOMPARE(window_->engine().tree()->depth, chosen);
        QVERIFY(!window_->state().depth);
        QCOMPARE(depth->value(), chosen);
        if (chosen != 7) {  // the later tests' depth
            depth->setValue(7);
            QVERIFY(built.wait(kWaitMs));
        }
        QCOMPARE(window_->engine().tree()->depth, 7);
    }

    void switchesRenderers() {
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("rendererCombo"));
        QVERIFY(combo);
        for (const QString& name : {QStringLiteral("direct"), QStringLiteral("area+colour"), QStringLiteral("full")}) {
            QVERIFY(combo->findText(name) >= 0);
            QSignalSpy frames(&window_->engine(), &Engine::frameReady);
            combo->setCurrentText(name);
            QVERIFY(frames.wait(kWaitMs));
            const auto r = frames.takeLast().at(0).value<FrameResult>();
            QCOMPARE(QString::fromStdString(r.panes.at(0).stats.renderer), name);
            QCOMPARE(window_->state().renderer, name.toStdString());
        }
    }

    void cameraFollowsMouseAndKeys() {
        RenderView* view = window_->view(0);
        const auto before = window_->viewCamera();
        QSignalSpy frames(window_, &MainWindow::frameShown);
        const QPoint c = view->rect().center();
        QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, c);
        QMouseEvent move(QEvent::MouseMove, QPointF(c + QPoint(60, 20)), view->mapToGlobal(QPointF(c + QPoint(60, 20))),
                         Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(view, &move);
        QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, c + QPoint(60, 20));
        QVERIFY(window_->state().cameraSet);
        const auto orbited = window_->viewCamera();
        QVERIFY(glm::length(orbited.position - before.position) > 1e-6);
        // Orbiting keeps the distance to the focal point.
        QVERIFY(std::abs(glm::length(orbited.position - orbited.lookAt) - glm::length(before.position - before.lookAt)) <
                1e-9 * glm::length(before.position - before.lookAt));
        QVERIFY(frames.wait(kWaitMs));
        QTest::keyClick(view, Qt::Key_Minus);  // zoom out one step
        const auto zoomed = window_->viewCamera();
        QVERIFY(glm::length(zoomed.position - zoomed.lookAt) > glm::length(orbited.position - orbited.lookAt));
        waitFrame();
        screenshot(QStringLiteral("studio-orbit.png"));
    }

    void latencyMeterAnswersEachInputOnce() {
        using Input = octrace::studio::LatencyMeter::Input;
        using namespace std::chrono_literals;
        octrace::studio::LatencyMeter m;
        const auto t0 = octrace::studio::LatencyMeter::Clock::now();
        QVERIFY(!m.painted(0, false, t0));  // a frame of no input answers nothing
        const auto a = m.input(Input::Move, t0);
        const auto b = m.input(Input::Move, t0 + 10ms);
        QCOMPARE(*m.painted(a, true, t0 + 30ms), 30.0);  // the frame requested after a, before b
        QCOMPARE(m.unanswered(), std::size_t(1));
        const auto c = m.input(Input::Finish, t0 + 40ms);
        QCOMPARE(m.latest(), c);
        QCOMPARE(*m.painted(c, false, t0 + 100ms), 90.0);  // b's wait, the longer of b and c
        QVERIFY(!m.painted(c, false, t0 + 120ms));         // painted again: nothing new
        QCOMPARE(m.samples().size(), std::size_t(3));
        QCOMPARE(m.samples()[0].ms, 30.0);
        QVERIFY(m.samples()[0].preview && !m.samples()[1].preview);
        QCOMPARE(m.samples()[1].ms, 90.0);
        QCOMPARE(m.samples()[2].ms, 60.0);
        QVERIFY(m.samples()[2].input == Input::Finish);
        QCOMPARE(b, a + 1);
    }

    void measuresInputToPaintLatency() {
        using Input = octrace::studio::LatencyMeter::Input;
        RenderView* view = window_->view(0);
        window_->latency().clear();
        QSignalSpy answered(window_, &MainWindow::inputAnswered);
        const QPoint c = view->rect().center();
        QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, c);
        for (int i = 1; i <= 3; ++i) {
            const QPointF at(c + QPoint(10 * i, 0));
            QMouseEvent move(QEvent::MouseMove, at, view->mapToGlobal(at), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
            QApplication::sendEvent(view, &move);
        }
        QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, c + QPoint(30, 0));
        // Three moves and the release, each answered once by a painted frame; the release by an exact one.
        QTRY_VERIFY_WITH_TIMEOUT(window_->latency().unanswered() == 0 && !window_->latency().samples().empty(), kWaitMs);
        const auto& s = window_->latency().samples();
        QCOMPARE(s.size(), std::size_t(4));
        QCOMPARE(std::count_if(s.begin(), s.end(), [](const auto& x) { return x.input == Input::Move; }), 3);
        QVERIFY(s.back().input == Input::Finish && !s.back().preview);
        for (const auto& x : s) QVERIFY(x.ms > 0.0 && x.ms < kWaitMs);
        QVERIFY(!answered.isEmpty());
        auto* label = window_->findChild<QLabel*>(QStringLiteral("latencyLabel"));
        QVERIFY(label && label->text().startsWith(QStringLiteral("input to paint ")));
    }

    void splitViewComparesTwoRenderers() {
        QAction* split = nullptr;
        QAction* difference = nullptr;
        for (QAction* a : window_->findChildren<QAction*>()) {
            if (a->text() == QStringLiteral("&Split View")) split = a;
            if (a->text() == QStringLiteral("&Difference Image")) difference = a;
        }
        QVERIFY(split && difference);
        auto* second = window_->findChild<QComboBox*>(QStringLiteral("secondRendererCombo"));
        second->setCurrentText(QStringLiteral("area+colour"));
        QSignalSpy frames(&window_->engine(), &Engine::frameReady);
        split->setChecked(true);
        FrameResult r;
        while (r.panes.size() != 2 || r.preview) {
            QVERIFY(frames.wait(kWaitMs));
            r = frames.takeLast().at(0).value<FrameResult>();
        }
        QVERIFY(window_->view(1)->isVisible());
        QCOMPARE(QString::fromStdString(r.panes[0].stats.renderer), QStringLiteral("full"));
        QCOMPARE(QString::fromStdString(r.panes[1].stats.renderer), QStringLiteral("area+colour"));
        QCOMPARE(r.panes[0].frame.width, r.panes[1].frame.width);
        QCOMPARE(r.fullMs, r.panes[0].stats.renderMs);  // full is one of the two
        // The count is the images' own comparison.
        qint64 differ = 0;
        for (int y = 0; y < r.panes[0].image.height(); ++y)
            for (int x = 0; x < r.panes[0].image.width(); ++x) differ += r.panes[0].image.pixel(x, y) != r.panes[1].image.pixel(x, y);
        QCOMPARE(qint64(r.mismatching), differ);
        difference->setChecked(true);
        r = FrameResult{};
        while (r.difference.isNull()) {
            QVERIFY(frames.wait(kWaitMs));
            r = frames.takeLast().at(0).value<FrameResult>();
        }
        QCOMPARE(r.difference.size(), r.panes[0].image.size());  // on screen already (the window's slot runs first)
        screenshot(QStringLiteral("studio-split.png"));
        difference->setChecked(false);
        split->setChecked(false);
        QVERIFY(!window_->view(1)->isVisible());
    }

    void openGlViewSplatsTheSurfels() {
        QAction* split = nullptr;
        for (QAction* a : window_->findChildren<QAction*>())
            if (a->text() == QStringLiteral("&Split View")) split = a;
        auto* second = window_->findChild<QComboBox*>(QStringLiteral("secondRendererCombo"));
        octrace::studio::SurfelView* gl = window_->surfelView();
        QSignalSpy drawn(gl, &octrace::studio::SurfelView::frameDrawn);
        second->setCurrentText(QStringLiteral("opengl"));
        split->setChecked(true);
        QVERIFY(drawn.wait(kWaitMs));
        while (drawn.wait(500)) {}  // the frames that follow the first (resizes, the exact camera)
        QVERIFY2(gl->rendererName().contains(QStringLiteral("llvmpipe")) || !gl->rendererName().contains(QStringLiteral("failed")),
                 qPrintable(gl->rendererName()));
        QCOMPARE(gl->surfelCount(), window_->engine().tree()->boundaryVoxels());
        // The splats cover what the CPU renderer draws from the same camera at the same size.
        const QImage splats = gl->grabFramebuffer().convertToFormat(QImage::Format_RGB32);
        octrace::Camera cam = octrace::studio::cameraFor(window_->state(), window_->engine().tree()->occupiedBounds(),
                                                          window_->engine().view(), splats.width(), splats.height());
        octrace::Frame frame;
        octrace::makeRenderer("full")->render(*window_->engine().tree(), cam, window_->engine().settingsFor(window_->state(), false), frame);
        const QImage cpu = octrace::studio::toImage(frame).convertToFormat(QImage::Format_RGB32);
        const QRgb bg = cpu.pixel(0, 0);
        qint64 both = 0, either = 0;
        // The statistics box at the top left is left out.
        for (int y = 100; y < cpu.height(); ++y)
            for (int x = 0; x < cpu.width(); ++x) {
                const bool a = cpu.pixel(x, y) != bg, b = splats.pixel(x, y) != bg;
                both += a && b;
                either += a || b;
            }
        QVERIFY(either > 1000);
        QVERIFY2(double(both) / double(either) > 0.9, qPrintable(QStringLiteral("overlap %1 of %2").arg(both).arg(either)));
        screenshot(QStringLiteral("studio-opengl.png"));
        // The mouse moves the camera in the OpenGL view as in the CPU views: an orbit, then the
        // wheel zooms.
        const auto before = window_->viewCamera();
        const QPoint c = gl->rect().center();
        QTest::mousePress(gl, Qt::LeftButton, Qt::NoModifier, c);
        QMouseEvent move(QEvent::MouseMove, QPointF(c + QPoint(-50, 30)), gl->mapToGlobal(QPointF(c + QPoint(-50, 30))),
                         Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(gl, &move);
        QTest::mouseRelease(gl, Qt::LeftButton, Qt::NoModifier, c + QPoint(-50, 30));
        octrace::Camera expected = before;
        octrace::studio::orbit(expected, -50 * 0.4, 30 * 0.4);
        const auto orbited = window_->viewCamera();
        QVERIFY(glm::length(orbited.position - expected.position) < 1e-9 * glm::length(before.position - before.lookAt));
        QWheelEvent wheel(QPointF(c), gl->mapToGlobal(QPointF(c)), QPoint(), QPoint(0, 120), Qt::NoButton, Qt::NoModifier,
                          Qt::NoScrollPhase, false);
        QApplication::sendEvent(gl, &wheel);
        const auto zoomed = window_->viewCamera();
        QVERIFY(glm::length(zoomed.position - zoomed.lookAt) < glm::length(orbited.position - orbited.lookAt));
        QVERIFY(drawn.wait(kWaitMs));  // the GL view draws the new camera
        split->setChecked(false);
        second->setCurrentText(QStringLiteral("direct"));
    }

    void exportsWhatTheCliRenders() {
        exportEqualsCli(QStringLiteral("full"), 320, 200, false);
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("rendererCombo"));
        combo->setCurrentText(QStringLiteral("direct"));
        exportEqualsCli(QStringLiteral("direct-transparent"), 240, 260, true);
        combo->setCurrentText(QStringLiteral("full"));
    }

    void surfaceControlDrawsAsTheCli() {
        // The `surface` setting: auto (unset) draws smooth with tile and voxel with full, as
        // render without --surface; voxel or smooth chosen holds for every renderer.
        openSample();
        auto* surface = window_->findChild<QComboBox*>(QStringLiteral("surface"));
        auto* renderer = window_->findChild<QComboBox*>(QStringLiteral("rendererCombo"));
        QVERIFY(surface && renderer);
        QCOMPARE(surface->currentIndex(), 0);
        QVERIFY(!window_->state().settings.count("surface"));
        renderer->setCurrentText(QStringLiteral("tile"));
        exportEqualsCli(QStringLiteral("surface-auto-tile"), 220, 160, false);
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        surface->setCurrentIndex(surface->findData(QStringLiteral("voxel")));
        QVERIFY(built.wait(kWaitMs));
        waitFrame();
        QCOMPARE(window_->state().settings.at("surface"), std::string("voxel"));
        QVERIFY(window_->engine().tree()->corners().empty());  // voxel builds no corner values
        QVERIFY(window_->commandLine(QStringLiteral("x.png"), 10, 10).join(QLatin1Char(' ')).contains(QStringLiteral("--surface voxel")));
        exportEqualsCli(QStringLiteral("surface-voxel-tile"), 220, 160, false);
        // (Exports, not the view: a frame of the renderer before may still be on its way.)
        QVERIFY(differingPixels(tmp_.filePath(QStringLiteral("surface-auto-tile-studio.png")),
                                tmp_.filePath(QStringLiteral("surface-voxel-tile-studio.png"))) > 100);
        // Smooth with a paper renderer, which draws voxel in auto.
        surface->setCurrentIndex(surface->findData(QStringLiteral("smooth")));
        QVERIFY(built.wait(kWaitMs));
        renderer->setCurrentText(QStringLiteral("full"));
        waitFrame();
        QVERIFY(!window_->engine().tree()->corners().empty());
        exportEqualsCli(QStringLiteral("surface-smooth-full"), 220, 160, false);
        // A session keeps it.
        const QString session = tmp_.filePath(QStringLiteral("surface-session.json"));
        QVERIFY(window_->saveSessionTo(session));
        surface->setCurrentIndex(0);
        QVERIFY(built.wait(kWaitMs));
        QVERIFY(!window_->state().settings.count("surface"));
        QVERIFY(window_->openSession(session));
        QVERIFY(built.wait(kWaitMs));
        QCOMPARE(surface->currentData().toString(), QStringLiteral("smooth"));
        surface->setCurrentIndex(0);
        QVERIFY(built.wait(kWaitMs));
        waitFrame();
    }

    void exportsFigureWithAnnotationsAsTheCli() {
        // A colour map brings the colour bar; title, subtitle, the box with its ticks and the
        // scale bar are the annotations, set at 200 dpi over a 900x640 figure.
        auto* colormap = window_->findChild<QComboBox*>(QStringLiteral("colormapCombo"));
        QVERIFY(colormap);
        colormap->setCurrentText(QStringLiteral("viridis"));
        waitFrame();
        window_->setFigure(true, QStringLiteral("Torus, coloured by height"), 200, true);
        const QStringList args = window_->commandLine(QStringLiteral("x.png"), 900, 640);
        for (const char* option : {"--figure", "--title", "--scale-bar", "--dpi"}) QVERIFY2(args.contains(QLatin1String(option)), option);
        exportEqualsCli(QStringLiteral("figure"), 900, 640, false);
        // The annotations are there: dark text in the title band (the plot starts below it) and
        // the colour bar's colours right of the plot.
        const QImage fig(tmp_.filePath(QStringLiteral("figure-studio.png")));
        const octrace::io::FigureLayout layout = *octrace::studio::figureLayoutFor(window_->state(), 900, 640);
        qint64 ink = 0;
        for (int y = 0; y < layout.plotY; ++y)
            for (int x = 0; x < fig.width(); ++x) ink += qGray(fig.pixel(x, y)) < 100;
        QVERIFY2(ink > 100, qPrintable(QString::number(ink)));
        QVERIFY(layout.barW > 0);
        const QRgb barMiddle = fig.pixel(layout.barX + layout.barW / 2, layout.barY + layout.barH / 2);
        QVERIFY(qGray(barMiddle) < 250 && qGray(barMiddle) > 5);
        window_->setFigure(false, QString(), 150, false);
        colormap->setCurrentIndex(0);
        waitFrame();
    }

    void exportDialogSetsTheFigure() {
        // File > Export Figure... as a user fills it in: a smaller figure (its dpi follows the
        // width: the annotations keep their share of the image), a title and a scale bar.
        const QString studioPng = tmp_.filePath(QStringLiteral("dialog-studio.png"));
        const QString cliPng = tmp_.filePath(QStringLiteral("dialog-cli.png"));
        int widthBefore = 0, dpiBefore = 0, dpiAfter = 0;
        bool filled = false;
        QSignalSpy exported(&window_->engine(), &Engine::exported);
        QVERIFY(runExportDialog([&](QDialog* dlg) {
            const auto [path, width, height, dpi, figure, title, scaleBar] = exportControls(dlg);
            if (exportControls(dlg).complete()) {
                path->setText(studioPng);
                widthBefore = width->value();
                dpiBefore = dpi->value();
                width->setValue(640);
                height->setValue(480);
                dpiAfter = dpi->value();
                figure->setChecked(true);
                title->setText(QStringLiteral("From the dialog"));
                scaleBar->setChecked(true);
                filled = true;
            }
            dlg->accept();
        }));
        QVERIFY(filled);
        QVERIFY(exported.wait(kWaitMs));
        QCOMPARE(dpiAfter, octrace::studio::scaledDpi(dpiBefore, widthBefore, 640));
        QVERIFY(widthBefore == 640 || dpiAfter != dpiBefore);
        QVERIFY(window_->state().figure && window_->state().scaleBar);
        QCOMPARE(window_->state().title, std::string("From the dialog"));
        QCOMPARE(window_->state().dpi, dpiAfter);
        QCOMPARE(QImage(studioPng).size(), QSize(640, 480));
        QCOMPARE(runCli(window_->commandLine(cliPng, 640, 480)), 0);
        QCOMPARE(differingPixels(studioPng, cliPng), 0);
        window_->setFigure(false, QString(), 150, false);
    }

    void exportDialogTypedWidthKeepsTheDpiInProportion() {
        openSample();
        // A width typed into the dialog goes through 1, 10 and 100 on the way to 1000: the dpi
        // follows the width typed, in proportion to the one the dialog opened with, not each
        // keystroke (it once climbed 36 -> 360 -> 1200 dpi and the figure was one giant title).
        const QString studioPng = tmp_.filePath(QStringLiteral("typed-studio.png"));
        const QString cliPng = tmp_.filePath(QStringLiteral("typed-cli.png"));
        int widthBefore = 0, dpiBefore = 0, dpiShown = 0;
        bool filled = false;
        QSignalSpy exported(&window_->engine(), &Engine::exported);
        QVERIFY(runExportDialog([&](QDialog* dlg) {
            const auto [path, width, height, dpi, figure, title, scaleBar] = exportControls(dlg);
            if (!exportControls(dlg).complete()) return;
            path->setText(studioPng);
            height->setValue(700);
            figure->setChecked(true);
            title->setText(QStringLiteral("A width typed"));
            widthBefore = width->value();
            dpiBefore = dpi->value();
            width->setFocus();
            width->selectAll();
            QTest::keyClicks(width, QStringLiteral("1000"));
            QTest::keyClick(width, Qt::Key_Return);  // as a user ends it: the default button (OK) exports
            dpiShown = dpi->value();
            filled = true;
            if (dlg->isVisible()) dlg->accept();
        }));
        QVERIFY(filled);
        const auto reset = qScopeGuard([this] { window_->setFigure(false, QString(), 150, false); });
        QSignalSpy failed(&window_->engine(), &Engine::failed);
        QTRY_VERIFY_WITH_TIMEOUT(exported.count() + failed.count() > 0, kWaitMs);  // the export has ended
        QVERIFY(widthBefore != 1000);
        const int expected = octrace::studio::scaledDpi(dpiBefore, widthBefore, 1000);
        QVERIFY2(dpiShown == expected, qPrintable(QStringLiteral("%1 dpi shown, %2 expected (%3 dpi at %4 px)")
                                                      .arg(dpiShown).arg(expected).arg(dpiBefore).arg(widthBefore)));
        QCOMPARE(window_->state().dpi, expected);
        QCOMPARE(exported.count(), 1);
        QCOMPARE(window_->state().exportWidth, 1000);
        // The figure is right: the CLI's for the same settings, pixel for pixel, and the plot
        // fills most of it (at 1200 dpi the title band alone was taller than the figure).
        QCOMPARE(QImage(studioPng).size(), QSize(1000, 700));
        QCOMPARE(runCli(window_->commandLine(cliPng, 1000, 700)), 0);
        QCOMPARE(differingPixels(studioPng, cliPng), 0);
        const auto layout = octrace::studio::figureLayoutFor(window_->state(), 1000, 700);
        QVERIFY(layout);
        QVERIFY2(layout->plotH > 700 / 2 && layout->plotW > 1000 / 2, qPrintable(QStringLiteral("plot %1x%2").arg(layout->plotW).arg(layout->plotH)));
    }

    void exportDialogKeepsTheLastFile() {
        openSample();
        // The file name (and its folder) of the last export is the dialog's next proposal, not
        // figure.png again.
        QVERIFY(QDir(tmp_.path()).mkpath(QStringLiteral("kept")));
        const QString kept = QFileInfo(tmp_.filePath(QStringLiteral("kept/last-export.png"))).absoluteFilePath();
        QSignalSpy exported(&window_->engine(), &Engine::exported);
        QVERIFY(runExportDialog([&](QDialog* dlg) {
            const ExportControls c = exportControls(dlg);
            if (!c.complete()) return;
            const auto [path, width, height, dpi, figure, title, scaleBar] = c;
            path->setText(kept);
            figure->setChecked(false);  // a plain image
            width->setValue(160);
            height->setValue(120);
            dlg->accept();
        }));
        QVERIFY(exported.wait(kWaitMs));
        QVERIFY(QFileInfo::exists(kept));
        QString proposed;
        QVERIFY(runExportDialog([&](QDialog* dlg) {
            if (QLineEdit* path = exportControls(dlg).path) proposed = path->text();
            dlg->reject();
        }));
        QCOMPARE(proposed, kept);
        // A dialog cancelled keeps the proposal too.
        QVERIFY(runExportDialog([&](QDialog* dlg) {
            if (QLineEdit* path = exportControls(dlg).path) proposed = path->text();
            dlg->reject();
        }));
        QCOMPARE(proposed, kept);
    }

    void lightingControlsMatchTheCli() {
        auto* ambient = window_->findChild<QDoubleSpinBox*>(QStringLiteral("ambientSpin"));
        auto* lighting = window_->findChild<QComboBox*>(QStringLiteral("lightingCombo"));
        auto* ao = window_->findChild<QSpinBox*>(QStringLiteral("bakeAoSpin"));
        QVERIFY(ambient && lighting && ao);
        // Dynamic lighting (a build: the octree's baked light follows the mode), then more
        // ambient light: only a frame.
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        lighting->setCurrentIndex(lighting->findData(QStringLiteral("dynamic")));
        QVERIFY(built.wait(kWaitMs));
        waitFrame();
        const QImage before = window_->view(0)->image();
        ambient->setValue(0.45);
        waitFrame();
        QCOMPARE(window_->state().ambient, 0.45);
        QVERIFY(window_->view(0)->image() != before);
        exportEqualsCli(QStringLiteral("dynamic-ambient"), 220, 160, false);
        // Shadow rays of the dynamic light: only a frame, the same as the CLI's.
        auto* shadows = window_->findChild<QCheckBox*>(QStringLiteral("shadowsCheck"));
        QVERIFY(shadows && shadows->isEnabled());
        const QImage unshadowed = window_->view(0)->image();
        shadows->setChecked(true);
        waitFrame();
        QVERIFY(window_->state().shadows);
        QVERIFY(window_->view(0)->image() != unshadowed);
        QVERIFY(window_->commandLine(QStringLiteral("x.png"), 10, 10).join(QLatin1Char(' ')).contains(QStringLiteral("--shadows on")));
        exportEqualsCli(QStringLiteral("dynamic-shadows"), 220, 160, false);
        shadows->setChecked(false);
        waitFrame();
        // Precomputed lighting: a build that bakes light, shadows and ambient occlusion.
        lighting->setCurrentIndex(lighting->findData(QStringLiteral("baked")));
        QVERIFY(built.wait(kWaitMs));
        QVERIFY(!window_->engine().tree()->baked().empty());
        QVERIFY(ao->isEnabled());
        ao->setValue(4);
        QVERIFY(built.wait(kWaitMs));
        QVERIFY(window_->commandLine(QStringLiteral("x.png"), 10, 10).contains(QStringLiteral("--bake-ao")));
        exportEqualsCli(QStringLiteral("baked"), 220, 160, false);
        // Back to the defaults: the octree loses its baked light again.
        lighting->setCurrentIndex(0);
        QVERIFY(built.wait(kWaitMs));
        QVERIFY(window_->engine().tree()->baked().empty());
        ambient->setValue(0.15);
        waitFrame();
    }

    void coherenceControlsMatchTheCli() {
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("rendererCombo"));
        auto* tolerance = window_->findChild<QDoubleSpinBox*>(QStringLiteral("colour_tolerance"));
        auto* branchUp = window_->findChild<QSpinBox*>(QStringLiteral("branch_up"));
        auto* miss = window_->findChild<QCheckBox*>(QStringLiteral("miss_coherence"));
        QVERIFY(combo && tolerance && branchUp && miss);
        // Enabled where a shown pane's renderer has them.
        QVERIFY(!window_->state().split);
        combo->setCurrentText(QStringLiteral("full"));
        QVERIFY(!tolerance->isEnabled() && !branchUp->isEnabled() && !miss->isEnabled());
        combo->setCurrentText(QStringLiteral("area-exact"));
        QVERIFY(!tolerance->isEnabled() && branchUp->isEnabled() && !miss->isEnabled());
        combo->setCurrentText(QStringLiteral("area+colour"));
        QVERIFY(tolerance->isEnabled() && branchUp->isEnabled() && miss->isEnabled());
        waitFrame();
        // Each changes the frame only, and the export equals the CLI's with the same options
        // (whose image differs from the defaults' one).
        const QImage before = window_->view(0)->image();
        tolerance->setValue(12.0);
        branchUp->setValue(2);
        miss->setChecked(false);
        waitFrame();
        QVERIFY(window_->view(0)->image() != before);
        QCOMPARE(window_->state().colourTolerance, 12.0f);
        QCOMPARE(window_->state().branchUp, 2);
        QVERIFY(!window_->state().missCoherence);
        const QString line = window_->commandLine(QStringLiteral("x.png"), 10, 10).join(QLatin1Char(' '));
        QVERIFY2(line.contains(QStringLiteral("--colour-tolerance 12 --branch-up 2 --miss-coherence off")), qPrintable(line));
        exportEqualsCli(QStringLiteral("coherence"), 220, 160, false);
        // Saved with the session and read back.
        const auto restored = octrace::studio::parseSession(octrace::studio::sessionJson(window_->state()));
        QCOMPARE(restored.colourTolerance, 12.0f);
        QCOMPARE(restored.branchUp, 2);
        QVERIFY(!restored.missCoherence);
        // The defaults again: no option on the command line.
        tolerance->setValue(3.0);
        branchUp->setValue(0);
        miss->setChecked(true);
        combo->setCurrentText(QStringLiteral("full"));
        waitFrame();
        QVERIFY(!window_->commandLine(QStringLiteral("x.png"), 10, 10).join(QLatin1Char(' ')).contains(QStringLiteral("coherence")));
    }

    void colourCoherenceOnFullMatchesTheCli() {
        // The CLI's --colour-coherence on a renderer without +colour: the check box, its session
        // member and the command line the studio gives.
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("rendererCombo"));
        auto* check = window_->findChild<QCheckBox*>(QStringLiteral("colour_coherence"));
        auto* tolerance = window_->findChild<QDoubleSpinBox*>(QStringLiteral("colour_tolerance"));
        QVERIFY(combo && check && tolerance);
        combo->setCurrentText(QStringLiteral("direct"));
        QVERIFY(!check->isEnabled());
        combo->setCurrentText(QStringLiteral("full"));
        QVERIFY(check->isEnabled() && !tolerance->isEnabled());
        waitFrame();
        const QImage before = window_->view(0)->image();
        check->setChecked(true);
        QVERIFY(tolerance->isEnabled());
        tolerance->setValue(40.0);
        waitFrame();
        QVERIFY(window_->state().colourCoherence);
        QVERIFY(window_->view(0)->image() != before);
        const QString line = window_->commandLine(QStringLiteral("x.png"), 10, 10).join(QLatin1Char(' '));
        QVERIFY2(line.contains(QStringLiteral("--colour-coherence --colour-tolerance 40")), qPrintable(line));
        exportEqualsCli(QStringLiteral("colour-coherence"), 220, 160, false);
        QVERIFY(octrace::studio::parseSession(octrace::studio::sessionJson(window_->state())).colourCoherence);
        check->setChecked(false);
        tolerance->setValue(3.0);
        waitFrame();
        QVERIFY(!window_->commandLine(QStringLiteral("x.png"), 10, 10).join(QLatin1Char(' ')).contains(QStringLiteral("coherence")));
    }

    void colourFillBackgroundMatchesTheCli() {
        // A setting bound to the options table (StudioState.h bindings()): its control, its
        // session member and the command line the studio gives come from the table and one line.
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("rendererCombo"));
        auto* fill = window_->findChild<QCheckBox*>(QString::fromLatin1(octrace::model::opt::colourFillBackground.key));
        QVERIFY(combo && fill);
        QCOMPARE(fill->property("octraceOption").toString(), QString::fromLatin1(octrace::model::opt::colourFillBackground.key));
        combo->setCurrentText(QStringLiteral("full"));
        QVERIFY(!fill->isEnabled());  // colour coherence is off: it would change nothing
        QSignalSpy frames(&window_->engine(), &Engine::frameReady);
        combo->setCurrentText(QStringLiteral("area+colour"));
        QVERIFY(fill->isEnabled());
        QVERIFY(frames.wait(kWaitMs));
        const std::uint64_t before = frames.takeLast().at(0).value<FrameResult>().panes.at(0).stats.colourFilled;
        fill->setChecked(true);
        QVERIFY(window_->state().colourFillsBackground);
        QVERIFY(frames.wait(kWaitMs));
        const std::uint64_t after = frames.takeLast().at(0).value<FrameResult>().panes.at(0).stats.colourFilled;
        QVERIFY2(after > before, qPrintable(QStringLiteral("%1 -> %2 pixels filled by colour").arg(before).arg(after)));
        const QString line = window_->commandLine(QStringLiteral("x.png"), 10, 10).join(QLatin1Char(' '));
        QVERIFY2(line.contains(QStringLiteral("--renderer area+colour")) && line.contains(QStringLiteral("--colour-fill-background")),
                 qPrintable(line));
        exportEqualsCli(QStringLiteral("colour-fill-background"), 220, 160, false);
        const QByteArray json = octrace::studio::sessionJson(window_->state());
        QVERIFY2(json.contains("\"colour_fill_background\": true"), json.constData());
        QVERIFY(octrace::studio::parseSession(json).colourFillsBackground);
        fill->setChecked(false);
        combo->setCurrentText(QStringLiteral("full"));
        waitFrame();
        QVERIFY(!window_->commandLine(QStringLiteral("x.png"), 10, 10).join(QLatin1Char(' ')).contains(QStringLiteral("fill")));
    }

    void cutAwayMatchesTheCli() {
        auto* cut = window_->findChild<QComboBox*>(QStringLiteral("cutCombo"));
        auto* edit = window_->findChild<QLineEdit*>(QStringLiteral("cutEdit"));
        auto* clip = window_->findChild<QCheckBox*>(QStringLiteral("clipCheck"));
        QVERIFY(cut && edit && clip);
        const std::size_t whole = window_->engine().tree()->boundaryVoxels();
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        for (const QString& kind : {QStringLiteral("box"), QStringLiteral("sphere"), QStringLiteral("halfspace")}) {
            cut->setCurrentIndex(cut->findData(kind));
            emit cut->activated(cut->currentIndex());  // as a user's choice
            QVERIFY(built.wait(kWaitMs));
            QVERIFY2(QString::fromStdString(window_->state().cut).startsWith(kind + QLatin1Char(':')), window_->state().cut.c_str());
            QCOMPARE(edit->text().toStdString(), window_->state().cut);
            QVERIFY(window_->engine().tree()->boundaryVoxels() != whole);
            if (kind == QLatin1String("box")) {
                waitFrame();
                // The controls in sight for the picture.
                if (auto* scroll = window_->findChild<QScrollArea*>()) scroll->ensureWidgetVisible(clip);
                screenshot(QStringLiteral("studio-cut.png"));
            }
            exportEqualsCli(QStringLiteral("cut-") + kind, 200, 150, false);
        }
        // A solid typed in, clipped to: what is left is inside the box.
        edit->setText(QStringLiteral("box:-0.2,-0.2,-1,0.9,0.9,1"));
        emit edit->editingFinished();
        QVERIFY(built.wait(kWaitMs));
        clip->setChecked(true);
        QVERIFY(built.wait(kWaitMs));
        QVERIFY(window_->commandLine(QStringLiteral("x.png"), 10, 10).contains(QStringLiteral("--clip")));
        const octrace::Box3 kept = window_->engine().tree()->occupiedBounds();
        QVERIFY2(kept.lo.x > -0.3 && kept.hi.x < 1.0, qPrintable(QStringLiteral("%1 %2").arg(kept.lo.x).arg(kept.hi.x)));
        exportEqualsCli(QStringLiteral("clip"), 200, 150, false);
        // A malformed solid is refused with a message; the cut stays.
        edit->setText(QStringLiteral("box:1,2"));
        emit edit->editingFinished();
        QCOMPARE(window_->state().cut, std::string("box:-0.2,-0.2,-1,0.9,0.9,1"));
        QVERIFY(window_->findChild<QWidget*>(QStringLiteral("errorBox")));
        for (auto* box : window_->findChildren<QWidget*>(QStringLiteral("errorBox"))) box->close();
        clip->setChecked(false);
        QVERIFY(built.wait(kWaitMs));
        cut->setCurrentIndex(0);
        emit cut->activated(0);
        QVERIFY(built.wait(kWaitMs));
        QVERIFY(window_->state().cut.empty());
        QCOMPARE(window_->engine().tree()->boundaryVoxels(), whole);
        waitFrame();
    }

    void sessionSavesAndRestoresTheState() {
        const QString path = tmp_.filePath(QStringLiteral("session.json"));
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("rendererCombo"));
        auto* colormap = window_->findChild<QComboBox*>(QStringLiteral("colormapCombo"));
        colormap->setCurrentIndex(1);
        combo->setCurrentText(QStringLiteral("direct"));
        waitFrame();
        screenshot(QStringLiteral("studio-colormap.png"));
        QVERIFY(window_->saveSessionTo(path));
        QFile file(path);
        QVERIFY(file.open(QIODevice::ReadOnly));
        const QByteArray saved = file.readAll();
        QVERIFY(saved.contains(QFileInfo(QStringLiteral("data_samples/torus.nrrd")).absoluteFilePath().toUtf8()));
        QCOMPARE(QFileInfo(path).dir().entryList(QDir::Files | QDir::Hidden).filter(QStringLiteral(".tmp")).size(), 0);
        // Change things, then open the session: the state comes back, the input is read again.
        combo->setCurrentText(QStringLiteral("full"));
        colormap->setCurrentIndex(0);
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        QSignalSpy failed(&window_->engine(), &Engine::failed);
        QVERIFY2(window_->openSession(path), saved.constData());
        QVERIFY2(built.wait(kWaitMs), failed.isEmpty() ? "" : qPrintable(failed.first().at(0).toString()));
        QCOMPARE(octrace::studio::sessionJson(window_->state()), saved);
        QCOMPARE(combo->currentText(), QStringLiteral("direct"));
        QCOMPARE(colormap->currentIndex(), 1);
        waitFrame();
        exportEqualsCli(QStringLiteral("session"), 200, 150, false);  // the colour map too

        // Missing and broken files: a message, and the state stays as it was.
        const QByteArray current = octrace::studio::sessionJson(window_->state());
        for (const QByteArray& bad : {QByteArray("{ not json"), QByteArray("[1, 2]"), QByteArray("{\"octrace_studio_session\": 3}"),
                                      QByteArray("{\"octrace_studio_session\": 1, \"surface\": {\"depth\": 99}}")}) {
            QFile f(tmp_.filePath(QStringLiteral("bad.json")));
            QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
            f.write(bad);
            f.close();
            QVERIFY(!window_->openSession(f.fileName()));
            QCOMPARE(octrace::studio::sessionJson(window_->state()), current);
        }
        QVERIFY(!window_->openSession(tmp_.filePath(QStringLiteral("missing.json"))));
        QCOMPARE(octrace::studio::sessionJson(window_->state()), current);
        for (auto* box : window_->findChildren<QWidget*>(QStringLiteral("errorBox"))) box->close();
        colormap->setCurrentIndex(0);
        combo->setCurrentText(QStringLiteral("full"));
    }

    void exportRefusesOversize() {
        QSignalSpy failed(&window_->engine(), &Engine::failed);
        window_->exportFigure(tmp_.filePath(QStringLiteral("huge.png")), octrace::studio::kMaxExportSide + 1, 10, false);
        QVERIFY(failed.wait(kWaitMs));
        QVERIFY(failed.takeFirst().at(0).toString().contains(QString::number(octrace::studio::kMaxExportSide)));
        QVERIFY(!QFileInfo::exists(tmp_.filePath(QStringLiteral("huge.png"))));
        QVERIFY(window_->state().exportWidth <= octrace::studio::kMaxExportSide);
        for (auto* box : window_->findChildren<QWidget*>(QStringLiteral("errorBox"))) box->close();
    }

    void cancelKeepsTheSurface() {
        auto* depth = window_->findChild<QSpinBox*>(QStringLiteral("depthSpin"));
        auto* cancel = window_->findChild<QPushButton*>(QStringLiteral("cancelButton"));
        QVERIFY(depth && cancel);
        const auto tree = window_->engine().tree();
        QSignalSpy progress(&window_->engine(), &Engine::progress);
        QSignalSpy cancelled(&window_->engine(), &Engine::cancelled);
        depth->setValue(12);  // long enough not to end before Cancel
        QVERIFY(progress.wait(kWaitMs));  // the build started
        QVERIFY(cancel->isEnabled());
        QTest::mouseClick(cancel, Qt::LeftButton);
        QVERIFY(cancelled.count() == 1 || cancelled.wait(kWaitMs));  // said at once when the job was still waiting
        QCOMPARE(window_->engine().tree(), tree);  // the previous surface stays
        QVERIFY(!window_->engine().building());
    }

    void cancelDuringTheReadKeepsTheScene() {
        // Reading a DICOM series is a stage of the progress bar ("Reading ...", in percent as
        // its files are scanned and decoded), and Cancel during it leaves the studio idle with
        // the scene on screen. Cancel is pressed from the first read percentage below 100, so
        // before the read's result is handed back, however fast the read is.
        auto* cancel = window_->findChild<QPushButton*>(QStringLiteral("cancelButton"));
        auto* bar = window_->findChild<QProgressBar*>(QStringLiteral("progress"));
        QVERIFY(cancel && bar);
        const auto tree = window_->engine().tree();
        QVERIFY(tree);
        const QByteArray before = octrace::studio::sessionJson(window_->state());
        const QString said = QStringLiteral("Cancelled; the previous surface stays");
        const qsizetype saidBefore = messagesText().count(said);
        QSignalSpy cancelled(&window_->engine(), &Engine::cancelled);
        QSignalSpy loaded(&window_->engine(), &Engine::inputLoaded);
        double readShown = -1.0;
        int barShown = -1;
        auto connection = connect(&window_->engine(), &Engine::progress, this, [&](const QString& stage, double f) {
            if (readShown >= 0.0 || !stage.startsWith(QStringLiteral("Reading")) || f < 0.0 || f >= 1.0) return;
            readShown = f;
            barShown = bar->maximum() == 100 ? bar->value() : -1;  // the window's slot ran first
            cancel->click();
        });
        window_->openInput(QStringLiteral(OCTRACE_TEST_DATA "/dicom/two_series"));
        QTRY_VERIFY2_WITH_TIMEOUT(cancelled.count() == 1, qPrintable(messagesText()), kWaitMs);
        disconnect(connection);
        QVERIFY(readShown >= 0.0);
        QCOMPARE(barShown, int(readShown * 100.0));
        QVERIFY(!window_->engine().building());
        QVERIFY(!cancel->isEnabled());
        QVERIFY(bar->isHidden());
        QVERIFY2(messagesText().count(said) == saidBefore + 1, qPrintable(messagesText()));
        // Nothing of the series arrives later: the scene and the window's state stay.
        QTest::qWait(300);
        QCOMPARE(loaded.count(), 0);
        QCOMPARE(window_->engine().tree(), tree);
        QCOMPARE(octrace::studio::sessionJson(window_->state()), before);
    }

    void brokenInputShowsAMessage() {
        const QString bad = tmp_.filePath(QStringLiteral("broken.nrrd"));
        QFile f(bad);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("NRRD0004\ntype: float\ndimension: 3\nsizes: 4 4\n\n");
        f.close();
        const auto tree = window_->engine().tree();
        const QByteArray before = octrace::studio::sessionJson(window_->state());
        QSignalSpy failed(&window_->engine(), &Engine::failed);
        window_->openInput(bad);
        QVERIFY(failed.wait(kWaitMs));
        QVERIFY(failed.takeFirst().at(0).toString().contains(bad));
        QCOMPARE(window_->engine().tree(), tree);
        QCOMPARE(octrace::studio::sessionJson(window_->state()), before);  // still the torus, as shown
        QVERIFY(window_->findChild<QWidget*>(QStringLiteral("errorBox")));
        for (auto* box : window_->findChildren<QWidget*>(QStringLiteral("errorBox"))) box->close();
    }

    void messagesNameTheStudiosControlsNotTheCliFlags() {
        // Core, io and the pipeline name settings by key; the studio says its controls' labels.
        // A log message of the build (the iso value chosen for the sample opened first) ...
        auto* messages = window_->findChild<QDockWidget*>(QStringLiteral("messagesDock"))->findChild<QPlainTextEdit*>();
        QVERIFY(messages);
        QVERIFY2(messages->toPlainText().contains(QStringLiteral("no 'Iso value' given")), qPrintable(messages->toPlainText()));
        QVERIFY(!messages->toPlainText().contains(QStringLiteral("--iso")));
        // ... and an error of the reader: a time step asked of a NRRD volume.
        auto* time = window_->findChild<QLineEdit*>(QStringLiteral("timeEdit"));
        QVERIFY(time);
        QSignalSpy failed(&window_->engine(), &Engine::failed);
        time->setText(QStringLiteral("3"));
        emit time->editingFinished();
        QVERIFY(failed.wait(kWaitMs));
        const QString error = failed.takeFirst().at(0).toString();
        QVERIFY2(error.contains(QStringLiteral("'Time' chooses a NetCDF time step")), qPrintable(error));
        QVERIFY2(!error.contains(QStringLiteral("--time")) && !error.contains(QLatin1Char('`')), qPrintable(error));
        time->setText(QString());
        emit time->editingFinished();
        for (auto* box : window_->findChildren<QWidget*>(QStringLiteral("errorBox"))) box->close();
    }

    void ctWindowPresetGreysLikeTheCli() {
        // A small CT series in HU (tests/data): two series, the larger chosen as by the CLI.
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        window_->openInput(QStringLiteral(OCTRACE_TEST_DATA "/dicom/two_series"));
        QVERIFY(built.wait(kWaitMs));
        QCOMPARE(window_->engine().info().units, QStringLiteral("HU"));
        QCOMPARE(window_->engine().info().series.size(), 2);
        QVERIFY(!window_->engine().window().valid());
        auto* windows = window_->findChild<QComboBox*>(QStringLiteral("windowCombo"));
        QVERIFY(windows);
        const int lung = windows->findData(QStringLiteral("lung"));
        QVERIFY(lung > 1);
        windows->setCurrentIndex(lung);  // a build with voxel values follows
        QVERIFY(built.wait(kWaitMs));
        QCOMPARE(window_->engine().window().centre, -600.0);
        QCOMPARE(window_->engine().window().width, 1500.0);
        QVERIFY(window_->commandLine(QStringLiteral("x.png"), 10, 10).contains(QStringLiteral("--window")));
        exportEqualsCli(QStringLiteral("ct-lung"), 160, 120, false);
        // The CLI's iso presets beside the iso value, for a field in HU; this small series holds
        // -1024 .. -989 HU only: skin (-500) and bone (300) would find no surface, and are off.
        auto* presets = window_->findChild<QComboBox*>(QStringLiteral("isoPresetCombo"));
        QVERIFY(presets && presets->isEnabled());
        auto* model = qobject_cast<QStandardItemModel*>(presets->model());
        QVERIFY(model);
        for (const char* name : {"skin", "bone"}) {
            const int i = presets->findData(QLatin1String(name));
            QVERIFY(i > 0);
            QVERIFY(!model->item(i)->isEnabled());
        }
        windows->setCurrentIndex(0);
    }

    void seriesBoxShowsTheSeriesRead() {
        // A folder with the LIDC chest CT as a series and, listed first (a lower SeriesNumber), a
        // 3-slice decoy: the reader takes the largest, the chest, and the Series box shows it.
        const std::string chestNrrd = OCTRACE_SHARED_DATA "/medical/lidc2_chest_ct.nrrd";
        if (!QFileInfo::exists(QString::fromStdString(chestNrrd))) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        const std::string folder = tmp_.filePath(QStringLiteral("chest_with_decoy")).toStdString();
        octrace::ScalarField chest = octrace::io::readField(chestNrrd);
        octrace::ScalarField decoy = chest.copy();
        decoy.dims.z = 3;
        decoy.values.resize(decoy.sampleCount());
        octrace::io::DicomSeriesWriteOptions o;
        o.description = "decoy";
        o.seriesNumber = 1;
        octrace::io::DicomSeriesWriter::write(decoy, folder + "/decoy", o);
        o.description = "chest";
        o.seriesNumber = 2;
        octrace::io::DicomSeriesWriter::write(chest, folder + "/chest", o);

        auto* series = window_->findChild<QComboBox*>(QStringLiteral("seriesCombo"));
        QVERIFY(series);
        // The z extent of the surface on screen: the chest's 133 slices of 2.5 mm, or the decoy's 5 mm.
        const auto height = [this] {
            const auto tree = window_->engine().tree();
            return tree ? tree->occupiedBounds().hi.z - tree->occupiedBounds().lo.z : 0.0;
        };
        QSignalSpy loaded(&window_->engine(), &Engine::inputLoaded);
        // The frames shown, and how many there were when the last surface was built: the first
        // frame of the chest can be shown before the checks below are done (waitFrame() would
        // then wait for one more that never comes).
        QSignalSpy frames(window_, &MainWindow::frameShown);
        qsizetype framesAtBuild = -1;
        const auto onBuilt = connect(&window_->engine(), &Engine::surfaceBuilt, this, [&] { framesAtBuild = frames.count(); });
        window_->openInput(QString::fromStdString(folder));
        QTRY_VERIFY2_WITH_TIMEOUT(!loaded.isEmpty() && window_->state().input == folder, qPrintable(messagesText()), kWaitMs);
        QCOMPARE(series->count(), 2);
        QVERIFY2(series->itemText(0).contains(QStringLiteral("decoy")), qPrintable(series->itemText(0)));
        QVERIFY2(series->currentText().contains(QStringLiteral("chest")) && series->currentText().contains(QStringLiteral("256x256x133")),
                 qPrintable(series->currentText()));
        QCOMPARE(series->currentIndex(), 1);
        QTRY_VERIFY_WITH_TIMEOUT(height() > 100.0, kWaitMs);  // what was built is the chest
        QTRY_VERIFY_WITH_TIMEOUT(framesAtBuild >= 0 && frames.count() > framesAtBuild, kWaitMs);  // and shown
        disconnect(onBuilt);
        sidePanel()->verticalScrollBar()->setValue(0);  // the Input box at the top
        screenshot(QStringLiteral("studio-series.png"));
    }

    void sidePanelFitsAt1600x1000() {
        // At 1600x1000 (and with the chest series' long names in the Series box) the side panel
        // shows all its controls: no horizontal scroll bar, nothing narrower than it needs.
        const QSize before = window_->size();
        window_->resize(1600, 1000);
        QTRY_COMPARE(window_->size(), QSize(1600, 1000));
        QTest::qWait(200);  // the docks' layout settles
        QScrollArea* panel = sidePanel();
        QVERIFY(panel);
        QWidget* content = panel->widget();
        QVERIFY2(!panel->horizontalScrollBar()->isVisible(), qPrintable(QStringLiteral("content needs %1 px, has %2 px")
                                                                      .arg(content->minimumSizeHint().width()).arg(panel->viewport()->width())));
        QVERIFY(panel->viewport()->width() >= content->minimumSizeHint().width());
        QVERIFY(content->width() >= content->minimumSizeHint().width());
        // ... and the render view keeps most of the window.
        QVERIFY2(window_->view(0)->width() > 1600 / 2, qPrintable(QString::number(window_->view(0)->width())));
        window_->resize(before);
        QTRY_COMPARE(window_->size(), before);
        waitFrame();
    }

    void wheelScrollsThePanelNotItsControls() {
        // The mouse wheel over the side panel scrolls it; a spin box, combo box or slider under
        // the pointer keeps its value unless it has the keyboard focus (it once turned the light).
        QScrollArea* panel = sidePanel();
        QVERIFY(panel);
        QScrollBar* bar = panel->verticalScrollBar();
        QVERIFY2(bar->maximum() > 0, "the panel must be taller than the dock for this test");
        window_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(window_));
        const QList<QWidget*> controls = wheelControls();
        QVERIFY(controls.size() >= 15);
        const QString sessionBefore = QString::fromUtf8(octrace::studio::sessionJson(window_->state()));
        int scrolled = 0;
        for (QWidget* c : controls) {
            if (QWidget* focused = QApplication::focusWidget()) focused->clearFocus();  // none has the focus
            QVERIFY(!c->hasFocus());
            panel->ensureWidgetVisible(c);
            const int at = bar->value();
            const QString value = controlValue(c);
            const int angle = at < bar->maximum() ? -120 : 120;  // down, or up at the end
            wheel(c, angle);
            QVERIFY2(controlValue(c) == value, qPrintable(QStringLiteral("%1 (%2) changed from %3 to %4")
                                                             .arg(c->objectName(), QLatin1String(c->metaObject()->className()), value, controlValue(c))));
            QVERIFY2(angle < 0 ? bar->value() > at : bar->value() < at, qPrintable(c->objectName()));
            ++scrolled;
        }
        QCOMPARE(scrolled, controls.size());
        QCOMPARE(QString::fromUtf8(octrace::studio::sessionJson(window_->state())), sessionBefore);
        // A control with the focus (clicked or tabbed into) takes the wheel.
        auto* light = window_->findChild<QDoubleSpinBox*>(QStringLiteral("lightx"));
        QVERIFY(light);
        panel->ensureWidgetVisible(light);
        light->setFocus();
        QTRY_VERIFY(light->hasFocus());
        const double x = light->value();
        wheel(light, 120);
        QVERIFY(light->value() != x);
        light->clearFocus();
        light->setValue(x);
        waitFrame();
    }

    // --- The radiology layout: slice panes beside the 3-D view (SliceViews.h) ---------------

    /// Opens the real chest CT in the four-up layout at 1600x1000 (false: the data is absent).
    bool openChestFourUp() {
        // As a user in the repository types it (../shared/data/...), for the screenshot.
        const QString chest = QDir::current().relativeFilePath(QStringLiteral(OCTRACE_SHARED_DATA "/medical/lidc2_chest_ct.nrrd"));
        if (!QFileInfo::exists(chest)) return false;
        auto* slices = window_->slices();
        if (window_->state().input == chest.toStdString() && slices->fourUp() && window_->size() == QSize(1600, 1000)) return true;
        if (window_->state().input != chest.toStdString()) {
            QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
            window_->openInput(chest);
            if (!built.wait(kWaitMs)) return false;
        }
        window_->resize(1600, 1000);
        if (!QTest::qWaitFor([this] { return window_->size() == QSize(1600, 1000); }, kWaitMs)) return false;
        QAction* fourUp = window_->findChild<QAction*>(QStringLiteral("layoutFourUp"));
        if (!fourUp) return false;
        QSignalSpy frames(window_, &MainWindow::frameShown);
        if (!slices->fourUp()) fourUp->trigger();
        QTest::qWait(200);  // the layout settles
        // A new layout or size draws a frame; when an earlier test left both as they are now,
        // none is due (the panes draw on the GUI thread at once).
        if (frames.isEmpty()) frames.wait(5000);
        return slices->fourUp();
    }

    /// Pane `i`'s image and the CLI's `slice` of the pane's own command line: 0 differing pixels.
    void paneEqualsCli(int i, const QString& stem) { QCOMPARE(paneDiffersFromCli(*window_->slices(), i, tmp_.path(), stem), 0); }

    void fourUpLayoutShowsTheThreeSlices() {
        if (!openChestFourUp()) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        auto* slices = window_->slices();
        const auto field = window_->engine().field();
        QVERIFY(field && field->patientLps);
        // Axial, coronal, sagittal, each through the middle sample (the CLI's default index, n/2).
        const octrace::SlicePlane planes[3] = {octrace::SlicePlane::Axial, octrace::SlicePlane::Coronal, octrace::SlicePlane::Sagittal};
        for (int i = 0; i < 3; ++i) {
            auto* pane = slices->pane(i);
            QVERIFY(pane->isVisible());
            QVERIFY2(pane->hasSlice(), qPrintable(pane->objectName()));
            QCOMPARE(pane->plane(), planes[i]);
            QVERIFY(pane->width() > 300 && pane->height() > 300);
            QVERIFY(surfacePixels(pane->image(), qRgb(0, 0, 0)) > 10000);  // the body, not black
        }
        QCOMPARE(slices->cursor(), octrace::ivec3(128, 128, 66));
        // The 3-D view shares the window: upper right, beside the axial pane.
        QVERIFY(window_->view(0)->isVisible());
        QVERIFY(window_->view(0)->mapTo(window_, QPoint(0, 0)).x() > slices->pane(0)->mapTo(window_, QPoint(0, 0)).x());
        // The orientation letters of `slice --figure`: axial seen from the feet, L on the right, A up.
        const auto& axial = slices->pane(0)->content();
        QCOMPARE(axial.letters[0], QStringLiteral("L"));
        QCOMPARE(axial.letters[1], QStringLiteral("R"));
        QCOMPARE(axial.letters[2], QStringLiteral("A"));
        QCOMPARE(axial.letters[3], QStringLiteral("P"));
        QCOMPARE(slices->pane(1)->content().letters[2], QStringLiteral("S"));
        QCOMPARE(slices->pane(2)->content().letters[0], QStringLiteral("P"));
        // The scale bar (scaleBarIsTheFiguresAtThePanesZoom checks its length).
        QVERIFY(axial.scaleBar.pixels > 10.0 && axial.scaleBar.pixels < axial.image.width());
        // The crosshair in the 3-D view.
        QVERIFY(window_->view(0)->marker().has_value());
        // The Input box names the file; its tooltip the path as given.
        auto* input = window_->findChild<QLabel*>(QStringLiteral("inputLabel"));
        QVERIFY(input);
        QCOMPARE(input->text(), QStringLiteral("lidc2_chest_ct.nrrd"));
        QCOMPARE(input->toolTip(), QString::fromStdString(window_->state().input));
        QCOMPARE(window_->windowTitle(), QStringLiteral("lidc2_chest_ct.nrrd - octrace studio"));
        if (!screenshots_.isEmpty()) {
            // The probe over the heart in the axial pane, as a user pointing at it sees it.
            auto* pane = slices->pane(0);
            const QPoint at(pane->width() / 2 + 10, pane->height() / 2 + 10);
            QMouseEvent move(QEvent::MouseMove, QPointF(at), pane->mapToGlobal(QPointF(at)), Qt::NoButton, Qt::NoButton, Qt::NoModifier);
            QApplication::sendEvent(pane, &move);
            QVERIFY(slices->probe().valid);
            sidePanel()->verticalScrollBar()->setValue(0);  // the Input box at the top
            screenshot(QStringLiteral("studio-fourup-ct.png"));
        }
    }

    /// The length in widget pixels of the scale bar `pane` paints: the longest run of white
    /// pixels along the bar's row, from its left end (10 px in) rightwards.
    static int paintedScaleBar(QWidget* pane) {
        const QImage shot = pane->grab().toImage().convertToFormat(QImage::Format_RGB32);
        const qreal dpr = shot.devicePixelRatio();
        const int y0 = int(std::lround((pane->height() - QFontMetrics(pane->font()).height() - 8) * dpr));
        int longest = 0;
        for (int y = std::max(0, y0 - 2); y <= std::min(shot.height() - 1, y0 + 1); ++y) {
            int x = int(10 * dpr), run = 0;
            while (x < shot.width() && (shot.pixel(x, y) & 0xFFFFFF) == 0xFFFFFF) ++x, ++run;
            longest = std::max(longest, run);
        }
        return int(std::lround(longest / dpr));
    }

    void scaleBarIsTheFiguresAtThePanesZoom() {
        // Each pane's scale bar is the one `slice --figure` draws for a view of the same mm per
        // pixel and width (model::sliceScaleBar, io::scaleBarLength: the largest 1, 2 or 5 x 10^k
        // mm of at most a fifth of the width), labelled as the figure labels it, and painted at
        // that length. At another zoom (a smaller window: more mm per pixel) it follows.
        if (!openChestFourUp()) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        auto* slices = window_->slices();
        const auto field = window_->engine().field();
        const auto check = [&](int i) {
            auto* pane = slices->pane(i);
            QVERIFY(pane->hasSlice());
            const auto& c = pane->content();
            const octrace::SliceView& v = c.result.view;
            const double mmPerPixel = v.pixelSize;
            const octrace::model::SliceScaleBar figure = octrace::model::sliceScaleBar(*field, v, false);
            QCOMPARE(c.scaleBar.length, figure.length);
            QCOMPARE(c.scaleBar.pixels, figure.pixels);
            QCOMPARE(c.scaleBar.label, figure.label);
            // The figure's rule, from the pane's mm per pixel and width.
            const double most = mmPerPixel * v.width / 5.0;
            QVERIFY2(c.scaleBar.length <= most * (1.0 + 1e-12) && c.scaleBar.length > most / 2.5 - 1e-9,
                     qPrintable(QStringLiteral("pane %1: %2 mm for at most %3 mm").arg(i).arg(c.scaleBar.length).arg(most)));
            const double k = std::pow(10.0, std::floor(std::log10(c.scaleBar.length) + 1e-9));
            const double m = c.scaleBar.length / k;
            QVERIFY2(std::abs(m - 1.0) < 1e-9 || std::abs(m - 2.0) < 1e-9 || std::abs(m - 5.0) < 1e-9, qPrintable(QString::number(m)));
            QCOMPARE(c.scaleBar.pixels, c.scaleBar.length / mmPerPixel);
            QCOMPARE(c.scaleBar.label, QString::number(c.scaleBar.length, 'g', 6).toStdString() + " mm");
            // Painted at that length (the pen's caps add a pixel or two).
            const int painted = paintedScaleBar(pane);
            const double expected = c.scaleBar.pixels / pane->devicePixelRatioF();
            QVERIFY2(std::abs(painted - expected) <= 2.0,
                     qPrintable(QStringLiteral("pane %1: painted %2 px, the bar is %3 px").arg(i).arg(painted).arg(expected)));
        };
        std::array<double, 3> mmPerPixel{}, length{};
        for (int i = 0; i < 3; ++i) {
            check(i);
            mmPerPixel[std::size_t(i)] = slices->pane(i)->content().result.view.pixelSize;
            length[std::size_t(i)] = slices->pane(i)->content().scaleBar.length;
        }
        // Another zoom: the window 640 high, the panes wide and low (the slice fits their height:
        // more mm per pixel, and more mm across), so the axial bar takes another round length.
        window_->resize(1600, 640);
        for (int i = 0; i < 3; ++i) {
            QTRY_VERIFY_WITH_TIMEOUT(slices->pane(i)->content().result.view.pixelSize > mmPerPixel[std::size_t(i)] * 1.5, kWaitMs);
            check(i);
        }
        QVERIFY2(slices->pane(0)->content().scaleBar.length > length[0],
                 qPrintable(QStringLiteral("%1 mm at %2 mm/px, %3 mm at %4 mm/px").arg(length[0]).arg(mmPerPixel[0])
                                .arg(slices->pane(0)->content().scaleBar.length).arg(slices->pane(0)->content().result.view.pixelSize)));
        window_->resize(1600, 1000);
        QTRY_COMPARE(window_->size(), QSize(1600, 1000));
        QTest::qWait(200);
    }

    void sliceWheelAndArrowKeysMoveExactlyOneSlice() {
        if (!openChestFourUp()) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        auto* slices = window_->slices();
        window_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(window_));
        for (int i = 0; i < 3; ++i) {
            auto* pane = slices->pane(i);
            const int start = slices->sliceIndex(i);
            const QImage before = pane->image();
            const octrace::ivec3 cursor = slices->cursor();
            wheel(pane, 120);  // one notch up: the next slice
            QCOMPARE(slices->sliceIndex(i), start + 1);
            QVERIFY(pane->image() != before);  // another slice on screen
            // Only this pane's slice moved; the other two stay.
            for (int a = 0; a < 3; ++a)
                if (a != octrace::sliceGridAxis(*window_->engine().field(), pane->plane())) QCOMPARE(slices->cursor()[a], cursor[a]);
            wheel(pane, -120);
            QCOMPARE(slices->sliceIndex(i), start);
            QCOMPARE(pane->image(), before);
            // A fine-grained wheel: half a notch does nothing, the second half one slice.
            wheel(pane, 60);
            QCOMPARE(slices->sliceIndex(i), start);
            wheel(pane, 60);
            QCOMPARE(slices->sliceIndex(i), start + 1);
            pane->setFocus();
            QTRY_VERIFY(pane->hasFocus());
            QTest::keyClick(pane, Qt::Key_Down);
            QCOMPARE(slices->sliceIndex(i), start);
            QTest::keyClick(pane, Qt::Key_Down);
            QCOMPARE(slices->sliceIndex(i), start - 1);
            QTest::keyClick(pane, Qt::Key_Up);
            QCOMPARE(slices->sliceIndex(i), start);
            QCOMPARE(pane->image(), before);
        }
        // At the last slice the wheel stops there.
        auto* axial = slices->pane(0);
        const int n = window_->engine().field()->dims.z;
        slices->step(0, n);
        QCOMPARE(slices->sliceIndex(0), n - 1);
        wheel(axial, 120);
        QCOMPARE(slices->sliceIndex(0), n - 1);
        slices->setCursor(octrace::ivec3(128, 128, 66));
    }

    /// Where world point `w` lies in a pane's image (pixel centres at +0.5), as the pane draws it.
    static QPointF imagePixelOf(const octrace::SliceView& v, const octrace::dvec3& w) {
        const octrace::dvec3 d = w - v.topLeft;
        const double ps2 = v.pixelSize * v.pixelSize;
        return {glm::dot(d, v.right) / ps2 + 0.5, glm::dot(d, v.down) / ps2 + 0.5};
    }
    /// The crosshair: the cursor is `voxel`, the coronal and sagittal slices pass through it, and
    /// each pane draws its lines there (within half a pixel).
    void crosshairIsAt(const octrace::ivec3& voxel) {
        auto* slices = window_->slices();
        const auto& field = *window_->engine().field();
        QCOMPARE(slices->cursor(), voxel);
        for (int i = 0; i < 3; ++i) {
            QCOMPARE(slices->sliceIndex(i), voxel[octrace::sliceGridAxis(field, slices->pane(i)->plane())]);
            const auto& content = slices->pane(i)->content();
            QVERIFY(content.crosshair.has_value());
            const QPointF expected = imagePixelOf(content.result.view, field.worldFromGrid(voxel.x, voxel.y, voxel.z));
            const QPointF off = *content.crosshair - expected;
            QVERIFY2(std::abs(off.x()) <= 0.5 && std::abs(off.y()) <= 0.5,
                     qPrintable(QStringLiteral("pane %1: crosshair at (%2, %3), the voxel at (%4, %5)")
                                    .arg(i).arg(content.crosshair->x()).arg(content.crosshair->y()).arg(expected.x()).arg(expected.y())));
        }
    }

    void clickInTheAxialPaneMovesTheOtherSlices() {
        // The crosshair is shared: a left click in the axial pane puts the coronal and sagittal
        // slices through the voxel clicked (the axial slice stays), and each pane draws its
        // lines there; a left drag carries them along to the voxel where it ends.
        if (!openChestFourUp()) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        auto* slices = window_->slices();
        auto* axial = slices->pane(0);
        const auto& field = *window_->engine().field();
        const int across = octrace::sliceGridAxis(field, axial->plane());
        const octrace::ivec3 start = slices->cursor();
        // The widget point over the centre of voxel `v` of the axial slice.
        const auto pointOf = [&](const octrace::ivec3& v) {
            const QPointF px = imagePixelOf(axial->content().result.view, field.worldFromGrid(v.x, v.y, v.z));
            return axial->widgetPoint(px);
        };
        // Mouse events at exact (sub-pixel) points, as a tablet or a scaled screen gives them.
        const auto send = [&](QEvent::Type type, QPointF at, Qt::MouseButton button, Qt::MouseButtons held) {
            QMouseEvent e(type, at, axial->mapToGlobal(at), button, held, Qt::NoModifier);
            QApplication::sendEvent(axial, &e);
        };
        octrace::ivec3 clicked = start, dragged = start;
        for (int a = 0; a < 3; ++a)
            if (a != across) {
                clicked[a] = field.dims[a] / 3;
                dragged[a] = field.dims[a] * 3 / 4;
            }
        const int coronal = slices->sliceIndex(1), sagittal = slices->sliceIndex(2);
        send(QEvent::MouseButtonPress, pointOf(clicked), Qt::LeftButton, Qt::LeftButton);
        send(QEvent::MouseButtonRelease, pointOf(clicked), Qt::LeftButton, Qt::NoButton);
        crosshairIsAt(clicked);
        QVERIFY(slices->sliceIndex(1) != coronal && slices->sliceIndex(2) != sagittal);  // both moved
        QCOMPARE(slices->sliceIndex(0), start[across]);
        paneEqualsCli(1, QStringLiteral("clicked-coronal"));
        paneEqualsCli(2, QStringLiteral("clicked-sagittal"));
        // A drag from there: the slices follow the pointer to where it is released.
        const QPointF from = pointOf(clicked), to = pointOf(dragged);
        send(QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
        for (int step = 1; step <= 4; ++step) send(QEvent::MouseMove, from + (to - from) * (step / 4.0), Qt::NoButton, Qt::LeftButton);
        send(QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
        crosshairIsAt(dragged);
        QCOMPARE(slices->sliceIndex(0), start[across]);
        paneEqualsCli(2, QStringLiteral("dragged-sagittal"));
        slices->setCursor(start);
    }

    void slicePanesEqualTheCliSlice() {
        if (!openChestFourUp()) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        auto* slices = window_->slices();
        // The NRRD has no window and is not in HU: the window is the 1st to 99th percentile of
        // its values (as for MR), and the CT presets are off.
        const auto field = window_->engine().field();
        std::vector<float> v;
        for (std::size_t k = 0; k < field->values.size(); ++k)
            if (field->isValid(k)) v.push_back(field->values[k]);
        std::sort(v.begin(), v.end());
        const double p1 = v[std::size_t(std::llround(0.01 * double(v.size() - 1)))];
        const double p99 = v[std::size_t(std::llround(0.99 * double(v.size() - 1)))];
        QVERIFY(p99 > p1);
        QCOMPARE(slices->window().centre, 0.5 * (p1 + p99));
        QCOMPARE(slices->window().width, p99 - p1);
        QVERIFY(slices->windowSource().contains(QStringLiteral("percentile")));
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("sliceWindowCombo"));
        QVERIFY(combo);
        auto* model = qobject_cast<QStandardItemModel*>(combo->model());
        QVERIFY(model);
        const int lung = combo->findData(QStringLiteral("lung"));
        QVERIFY(lung > 0);
        QVERIFY(!model->item(lung)->isEnabled());
        // Each pane: the CLI's slice at the same plane, index, size and window, pixel for pixel.
        for (int i = 0; i < 3; ++i) paneEqualsCli(i, QStringLiteral("pane%1").arg(i));
        // Another slice, then a window set by a right drag: still the CLI's.
        slices->step(0, -20);
        auto* axial = slices->pane(0);
        const auto before = slices->window();
        const QPoint c = axial->rect().center();
        QTest::mousePress(axial, Qt::RightButton, Qt::NoModifier, c);
        QMouseEvent move(QEvent::MouseMove, QPointF(c + QPoint(40, -25)), axial->mapToGlobal(QPointF(c + QPoint(40, -25))), Qt::NoButton,
                         Qt::RightButton, Qt::NoModifier);
        QApplication::sendEvent(axial, &move);
        QTest::mouseRelease(axial, Qt::RightButton, Qt::NoModifier, c + QPoint(40, -25));
        QVERIFY(slices->window().width > before.width);    // dragged right: wider
        QVERIFY(slices->window().centre > before.centre);  // dragged up: a higher level
        QCOMPARE(combo->currentData().toInt(), 1000);      // "Custom (dragged)"
        paneEqualsCli(0, QStringLiteral("dragged"));
        // Left drag in window/level mode does the same; the crosshair stays.
        auto* wl = window_->findChild<QToolButton*>(QStringLiteral("windowLevelButton"));
        QVERIFY(wl);
        wl->setChecked(true);
        const auto cursor = slices->cursor();
        const auto dragged = slices->window();
        QTest::mousePress(axial, Qt::LeftButton, Qt::NoModifier, c);
        QMouseEvent left(QEvent::MouseMove, QPointF(c + QPoint(-30, 0)), axial->mapToGlobal(QPointF(c + QPoint(-30, 0))), Qt::NoButton,
                         Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(axial, &left);
        QTest::mouseRelease(axial, Qt::LeftButton, Qt::NoModifier, c + QPoint(-30, 0));
        QVERIFY(slices->window().width < dragged.width);
        QCOMPARE(slices->cursor(), cursor);
        wl->setChecked(false);
        // Back to automatic.
        combo->setCurrentIndex(0);
        QCOMPARE(slices->window().width, p99 - p1);
        slices->setCursor(octrace::ivec3(128, 128, 66));
    }

    void ctPresetWindowsTheSlicesAsTheCli() {
        // A CT series in HU (tests/data): the presets are on, and a pane with one equals the
        // CLI's `slice --window lung`.
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        window_->openInput(QStringLiteral(OCTRACE_TEST_DATA "/dicom/two_series"));
        QVERIFY(built.wait(kWaitMs));
        auto* slices = window_->slices();
        slices->setFourUp(true);
        waitFrame();
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("sliceWindowCombo"));
        auto* model = qobject_cast<QStandardItemModel*>(combo->model());
        const int lung = combo->findData(QStringLiteral("lung"));
        QVERIFY(model->item(lung)->isEnabled());
        combo->setCurrentIndex(lung);
        QCOMPARE(slices->window().centre, -600.0);
        QCOMPARE(slices->window().width, 1500.0);
        QVERIFY(slices->commandLine(0, QStringLiteral("x.png")).contains(QStringLiteral("lung")));
        for (int i = 0; i < 3; ++i) paneEqualsCli(i, QStringLiteral("lung%1").arg(i));
    }

    void mrWindowsFromItsPercentiles() {
        // A real MR (multi-frame, 64x64x10, no stored window, not in HU): no presets, the
        // automatic window from its 1st to 99th percentile, and the panes equal the CLI's slice.
        const QString mr = QStringLiteral(OCTRACE_SHARED_DATA "/medical/emri_small.dcm");
        if (!QFileInfo::exists(mr)) QSKIP("needs ../shared/data/medical/emri_small.dcm");
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        window_->openInput(mr);
        QVERIFY(built.wait(kWaitMs));
        auto* slices = window_->slices();
        slices->setFourUp(true);
        const auto field = window_->engine().field();
        QVERIFY(field && field->patientLps && !field->window.valid());
        std::vector<float> v(field->values.begin(), field->values.end());
        std::sort(v.begin(), v.end());
        const double p1 = v[std::size_t(std::llround(0.01 * double(v.size() - 1)))];
        const double p99 = v[std::size_t(std::llround(0.99 * double(v.size() - 1)))];
        QCOMPARE(slices->window().centre, 0.5 * (p1 + p99));
        QCOMPARE(slices->window().width, p99 - p1);
        QVERIFY(slices->window().width < double(v.back() - v.front()));  // not the whole range
        auto* combo = window_->findChild<QComboBox*>(QStringLiteral("sliceWindowCombo"));
        auto* model = qobject_cast<QStandardItemModel*>(combo->model());
        QVERIFY(!model->item(combo->findData(QStringLiteral("brain")))->isEnabled());
        for (int i = 0; i < 3; ++i) paneEqualsCli(i, QStringLiteral("mr%1").arg(i));
        // Ten slices along z: the wheel walks them one by one.
        slices->setCursor(octrace::ivec3(32, 32, 0));
        for (int k = 1; k < field->dims.z; ++k) {
            wheel(slices->pane(0), 120);
            QCOMPARE(slices->sliceIndex(0), k);
        }
        waitFrame();
    }

    void probeShowsTheCliSliceValue() {
        if (!openChestFourUp()) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        auto* slices = window_->slices();
        // The CLI's slice of each pane with the window 127.5/255 over the chest's 0..255: its
        // PNG holds round(value), so the probe's value must round to the CLI's grey.
        for (int i = 0; i < 3; ++i) {
            auto* pane = slices->pane(i);
            QStringList args = slices->commandLine(i, tmp_.filePath(QStringLiteral("probe%1.png").arg(i)));
            const int w = int(args.indexOf(QStringLiteral("--window")));
            QVERIFY(w > 0);
            args[w + 1] = QStringLiteral("127.5,255");
            QCOMPARE(runSlice(args), 0);
            const QImage cli = QImage(tmp_.filePath(QStringLiteral("probe%1.png").arg(i))).convertToFormat(QImage::Format_RGBA8888);
            QCOMPARE(cli.size(), pane->imageSize());
            int probed = 0;
            for (const QPoint at : {QPoint(pane->width() / 2, pane->height() / 2), QPoint(pane->width() / 3, pane->height() / 2 + 17),
                                    QPoint(pane->width() / 2 + 23, pane->height() / 3)}) {
                QMouseEvent move(QEvent::MouseMove, QPointF(at), pane->mapToGlobal(QPointF(at)), Qt::NoButton, Qt::NoButton, Qt::NoModifier);
                QApplication::sendEvent(pane, &move);
                const auto& probe = slices->probe();
                QVERIFY2(probe.valid, qPrintable(probe.text));
                const QPointF px = pane->imagePixel(QPointF(at));
                const int grey = qRed(cli.pixel(int(px.x()), int(px.y())));
                QVERIFY2(std::abs(probe.value - grey) <= 0.5 + 1e-3,
                         qPrintable(QStringLiteral("probe %1, CLI grey %2 at %3,%4").arg(probe.value).arg(grey).arg(px.x()).arg(px.y())));
                // The position: the pixel's centre in LPS, and in RAS (x and y negated).
                const octrace::dvec3 world = pane->content().result.view.world(std::floor(px.x()), std::floor(px.y()));
                QVERIFY(glm::length(probe.world - world) < 1e-9);
                auto num = [](double x) { return QString::number(x, 'g', 6); };
                QVERIFY2(probe.text.contains(QStringLiteral("LPS (%1, %2, %3) mm").arg(num(world.x), num(world.y), num(world.z))),
                         qPrintable(probe.text));
                QVERIFY2(probe.text.contains(QStringLiteral("RAS (%1, %2, %3) mm").arg(num(-world.x + 0.0), num(-world.y + 0.0), num(world.z))),
                         qPrintable(probe.text));
                auto* label = window_->findChild<QLabel*>(QStringLiteral("probeLabel"));
                QVERIFY(label && label->isVisible());
                QCOMPARE(label->text(), probe.text);
                ++probed;
            }
            QCOMPARE(probed, 3);
        }
    }

    void sessionKeepsTheLayoutCrosshairAndWindow() {
        if (!openChestFourUp()) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        auto* slices = window_->slices();
        const auto field = window_->engine().field();
        // A crosshair off the middle, the sagittal slice between two samples (placed by its
        // position box, the CLI's --at), a window dragged to 60/120.
        slices->setCursor(octrace::ivec3(100, 140, 50));
        const auto [lo, hi] = octrace::model::sliceAtRange(*field, octrace::SlicePlane::Sagittal);
        const double x = lo + 0.3137 * (hi - lo);
        slices->setAt(2, x);
        QVERIFY(slices->setWindowText("60,120"));
        const octrace::ivec3 cursor = slices->cursor();
        QCOMPARE(cursor.y, 140);
        const QString path = tmp_.filePath(QStringLiteral("layout.json"));
        QVERIFY(window_->saveSessionTo(path));
        const auto saved = octrace::studio::loadSession(path);
        QVERIFY(saved.fourUp);
        QVERIFY(saved.crosshair == cursor);
        QVERIFY(saved.sliceAt[2] == x);
        QVERIFY(!saved.sliceAt[0] && !saved.sliceAt[1]);
        QCOMPARE(saved.sliceWindow, std::string("60,120"));
        QFile file(path);
        QVERIFY(file.open(QIODevice::ReadOnly));
        const QByteArray json = file.readAll();  // the input as an absolute path
        const QImage sagittal = slices->pane(2)->image();
        // Elsewhere: the 3-D view alone, the middle sample, the automatic window.
        window_->findChild<QAction*>(QStringLiteral("layout3d"))->trigger();
        slices->setCursor(octrace::ivec3(128, 128, 66));
        slices->choosePreset(QString());
        QVERIFY(!window_->state().fourUp);
        // Opened: the layout at once; the input is read again, then the crosshair, the sagittal
        // position and the window come back as saved.
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        QVERIFY(window_->openSession(path));
        QVERIFY(slices->fourUp());
        QVERIFY(built.wait(kWaitMs));
        QCOMPARE(slices->cursor(), cursor);
        QVERIFY(slices->at(2) == x);
        QVERIFY(!slices->at(0) && !slices->at(1));
        QCOMPARE(slices->window().centre, 60.0);
        QCOMPARE(slices->window().width, 120.0);
        QCOMPARE(octrace::studio::sessionJson(window_->state()), json);
        QCOMPARE(slices->pane(2)->image(), sagittal);
        QVERIFY(slices->commandLine(2, QStringLiteral("x.png")).contains(QStringLiteral("--at")));
        paneEqualsCli(2, QStringLiteral("restored"));
        // A session of format version 1 (no layout) opens with the panes as a new window has them.
        const auto old = octrace::studio::parseSession(R"({"octrace_studio_session": 1, "input": {"path": "/x/a.nrrd"}})");
        QVERIFY(!old.fourUp && !old.crosshair && !old.sliceAt[0] && old.sliceWindow.empty());
        slices->setCursor(octrace::ivec3(128, 128, 66));
        slices->choosePreset(QString());
    }

    void clickOnTheSurfaceMovesTheSlicesThere() {
        if (!openChestFourUp()) QSKIP("needs ../shared/data/medical/lidc2_chest_ct.nrrd");
        auto* slices = window_->slices();
        RenderView* view = window_->view(0);
        // The frame on screen, and its camera: where the surface is.
        QSignalSpy frames(&window_->engine(), &Engine::frameReady);
        QTest::keyClick(view, Qt::Key_Left);  // an exact frame follows the key
        QTRY_VERIFY_WITH_TIMEOUT(!frames.isEmpty() && !frames.last().at(0).value<FrameResult>().preview, kWaitMs);
        const FrameResult r = frames.last().at(0).value<FrameResult>();
        const octrace::Frame& frame = r.panes[0].frame;
        const auto field = window_->engine().field();
        const double iso = window_->engine().iso();
        int tried = 0;
        for (const QPoint at : {QPoint(view->width() / 2, view->height() / 2), QPoint(view->width() / 2 - 40, view->height() / 2 + 30),
                                QPoint(view->width() / 2 + 35, view->height() / 2 - 25)}) {
            const std::size_t k = frame.pixel(at.x(), at.y());
            if (frame.hitId[k] == octrace::kNoHit) continue;
            ++tried;
            const octrace::Ray ray = r.camera.primaryRay(at.x(), at.y());
            const octrace::dvec3 hit = ray.origin + double(frame.depth[k]) * ray.direction;
            slices->setCursor(octrace::ivec3(0, 0, 0));
            QTest::mouseClick(view, Qt::LeftButton, Qt::NoModifier, at);
            const octrace::ivec3 c = slices->cursor();
            // The three slices pass through the picked sample ...
            QCOMPARE(slices->sliceIndex(0), c.z);
            QCOMPARE(slices->sliceIndex(1), c.y);
            QCOMPARE(slices->sliceIndex(2), c.x);
            // ... within one voxel of the surface point under the pointer ...
            const octrace::dvec3 w = field->worldFromGrid(c.x, c.y, c.z);
            for (int a = 0; a < 3; ++a)
                QVERIFY2(std::abs(w[a] - hit[a]) <= field->spacing[a] + 1e-9,
                         qPrintable(QStringLiteral("axis %1: sample at %2, surface at %3").arg(a).arg(w[a]).arg(hit[a])));
            // ... on the surface: samples within one of the octree's voxels of it (larger than a
            // sample at a low depth) lie on both sides of the iso value.
            const double voxel = window_->engine().tree()->voxelSize();
            const octrace::ivec3 reach(int(std::ceil(voxel / field->spacing.x)), int(std::ceil(voxel / field->spacing.y)),
                                       int(std::ceil(voxel / field->spacing.z)));
            bool below = false, above = false;
            for (int dz = -reach.z; dz <= reach.z; ++dz)
                for (int dy = -reach.y; dy <= reach.y; ++dy)
                    for (int dx = -reach.x; dx <= reach.x; ++dx) {
                        const octrace::ivec3 s = glm::clamp(c + octrace::ivec3(dx, dy, dz), octrace::ivec3(0), field->dims - 1);
                        const float v = field->values[field->index(s.x, s.y, s.z)];
                        below = below || v < iso;
                        above = above || v >= iso;
                    }
            QVERIFY2(below && above, qPrintable(QStringLiteral("depth %1, voxel %2 mm").arg(window_->engine().depth()).arg(voxel)));
            // The 3-D view's crosshair mark lies where it was clicked (the voxel's centre, not the hit point: a few pixels).
            QVERIFY(view->marker().has_value());
            QVERIFY2(QLineF(*view->marker(), QPointF(at) + QPointF(0.5, 0.5)).length() < 8.0,
                     qPrintable(QStringLiteral("%1,%2").arg(view->marker()->x()).arg(view->marker()->y())));
        }
        QVERIFY(tried >= 2);
        // A click on the background moves nothing.
        const octrace::ivec3 before = slices->cursor();
        QTest::mouseClick(view, Qt::LeftButton, Qt::NoModifier, QPoint(3, 3));
        QCOMPARE(slices->cursor(), before);
        // Back to the 3-D view alone.
        window_->findChild<QAction*>(QStringLiteral("layout3d"))->trigger();
        QVERIFY(!slices->pane(0)->isVisible());
        QVERIFY(!view->marker().has_value());
        window_->resize(1000, 640);
        waitFrame();
    }

    void sessionParserChecksEveryMember_data() {
        QTest::addColumn<QByteArray>("json");
        QTest::addColumn<QString>("message");
        auto row = [](const char* name, const char* body, const char* message) {
            QTest::newRow(name) << QByteArray(body) << QString::fromLatin1(message);
        };
        row("not json", "{", "JSON error");
        row("no version", "{}", "no 'octrace_studio_session' member");
        row("version", R"({"octrace_studio_session": 3})", "format version 3");
        row("four_up", R"({"octrace_studio_session": 2, "layout": {"four_up": 1}})", "layout.four_up: must be true or false");
        row("crosshair fraction", R"({"octrace_studio_session": 2, "layout": {"crosshair": [1.5, 2, 3]}})",
            "layout.crosshair: 1.5 is not a whole number");
        row("crosshair negative", R"({"octrace_studio_session": 2, "layout": {"crosshair": [-1, 2, 3]}})",
            "layout.crosshair: -1 is outside");
        row("crosshair short", R"({"octrace_studio_session": 2, "layout": {"crosshair": [1, 2]}})",
            "layout.crosshair: must be an array of 3 numbers");
        row("slice_at", R"({"octrace_studio_session": 2, "layout": {"slice_at": [1, "x", null]}})",
            "layout.slice_at: must be an array of 3 numbers or nulls");
        row("slice_window", R"({"octrace_studio_session": 2, "layout": {"slice_window": "wide"}})", "layout.slice_window: ");
        row("slice_window none", R"({"octrace_studio_session": 2, "layout": {"slice_window": "none"}})", "layout.slice_window: ");
        row("input type", R"({"octrace_studio_session": 1, "input": {"path": 5}})", "input.path: must be a string");
        row("depth", R"({"octrace_studio_session": 1, "surface": {"depth": 0}})", "surface.depth: 0 is outside");
        row("depth fraction", R"({"octrace_studio_session": 1, "surface": {"depth": 7.5}})", "surface.depth: 7.5 is not a whole number");
        row("iso", R"({"octrace_studio_session": 1, "surface": {"iso": "x"}})", "surface.iso: must be a number");
        row("renderer", R"({"octrace_studio_session": 1, "renderers": {"main": "warp"}})", "renderers.main: unknown renderer 'warp'");
        row("fov", R"({"octrace_studio_session": 1, "camera": {"fov": 180}})", "camera.fov: 180 is outside (0, 180) degrees");
        row("camera partial", R"({"octrace_studio_session": 1, "camera": {"position": [1, 2, 3]}})", "go together");
        row("camera degenerate",
            R"({"octrace_studio_session": 1, "camera": {"position": [1, 1, 1], "look_at": [1, 1, 1], "up": [0, 0, 1]}})",
            "camera.position:");
        row("light zero", R"({"octrace_studio_session": 1, "shading": {"light": [0, 0, 0]}})", "shading.light: direction must not be zero");
        row("colour range", R"({"octrace_studio_session": 1, "shading": {"colour": [1, 2, 0]}})", "shading.colour: 2 is outside");
        row("colour name", R"({"octrace_studio_session": 1, "shading": {"colour": "tomatoes"}})",
            "shading.colour: unknown colour name 'tomatoes'");
        // (Not raw strings: moc's preprocessor takes a '#' inside one for a directive.)
        row("colour hex alpha", "{\"octrace_studio_session\": 1, \"shading\": {\"colour\": \"#ff634780\"}}", "shading.colour: expected");
        row("colormap", R"({"octrace_studio_session": 1, "shading": {"colormap": "rainbow2"}})", "unknown colour map 'rainbow2'");
        row("export size", R"({"octrace_studio_session": 1, "export": {"width": 16385}})", "export.width: 16385 is outside");
        row("window", R"({"octrace_studio_session": 1, "shading": {"window": "liver"}})", "shading.window:");
        row("window and colormap", R"({"octrace_studio_session": 1, "shading": {"window": "bone", "colormap": "viridis"}})",
            "both colour the surface");
        row("section type", R"({"octrace_studio_session": 1, "export": []})", "export: must be an object");
        row("ambient", R"({"octrace_studio_session": 1, "shading": {"ambient": 1.5}})", "shading.ambient: 1.5 is outside");
        row("lighting", R"({"octrace_studio_session": 1, "shading": {"lighting": "sunny"}})", "shading.lighting: expected");
        row("bake ao", R"({"octrace_studio_session": 1, "shading": {"bake_ao": -1}})", "shading.bake_ao: -1 is outside");
        row("shadows type", R"({"octrace_studio_session": 1, "shading": {"shadows": "on"}})", "shading.shadows: must be true or false");
        row("cut", R"({"octrace_studio_session": 1, "surface": {"cut": "box:1,2"}})", "surface.cut:");
        row("relief without a file", R"({"octrace_studio_session": 1, "surface": {"cut": "relief:"}})", "surface.cut:");
        row("clip type", R"({"octrace_studio_session": 1, "surface": {"clip": 1}})", "surface.clip: must be true or false");
        row("dpi", R"({"octrace_studio_session": 1, "export": {"dpi": 20}})", "export.dpi: 20 is outside");
        row("title type", R"({"octrace_studio_session": 1, "export": {"title": 3}})", "export.title: must be a string");
        row("colour tolerance", R"({"octrace_studio_session": 1, "renderers": {"colour_tolerance": 300}})",
            "renderers.colour_tolerance: 300 is outside [0, 255]");
        row("branch up", R"({"octrace_studio_session": 1, "renderers": {"branch_up": 1.5}})", "renderers.branch_up: 1.5 is not a whole number");
        row("miss coherence type", R"({"octrace_studio_session": 1, "renderers": {"miss_coherence": "off"}})",
            "renderers.miss_coherence: must be true or false");
    }

    void sessionParserChecksEveryMember() {
        QFETCH(QByteArray, json);
        QFETCH(QString, message);
        try {
            octrace::studio::parseSession(json);
            QFAIL("expected InputError");
        } catch (const octrace::InputError& e) {
            QVERIFY2(QString::fromStdString(e.what()).contains(message), e.what());
        }
    }

    void sessionParserReadsTheLayout() {
        const auto s = octrace::studio::parseSession(
            R"({"octrace_studio_session": 2, "layout": {"four_up": true, "crosshair": [3, 4, 5], "slice_at": [450.5, null, -30],
                "slice_window": "bone"}})");
        QVERIFY(s.fourUp);
        QVERIFY(s.crosshair == octrace::ivec3(3, 4, 5));
        QVERIFY(s.sliceAt[0] == 450.5 && !s.sliceAt[1] && s.sliceAt[2] == -30.0);
        QCOMPARE(s.sliceWindow, std::string("bone"));
        // Written and read back as it was; a version 1 session has none of it.
        QCOMPARE(octrace::studio::sessionJson(octrace::studio::parseSession(octrace::studio::sessionJson(s))), octrace::studio::sessionJson(s));
        QVERIFY(octrace::studio::sessionJson(s).contains("\"octrace_studio_session\": 2"));
        const auto old = octrace::studio::parseSession(R"({"octrace_studio_session": 1})");
        QVERIFY(!old.fourUp && !old.crosshair && !old.sliceAt[2] && old.sliceWindow.empty());
    }

    void sessionParserKeepsDefaultsAndResolvesRelativeInputs() {
        const auto s = octrace::studio::parseSession(R"({"octrace_studio_session": 1, "input": {"path": "data/a.nc"}})", QStringLiteral("/base"));
        QCOMPARE(QString::fromStdString(s.input), QStringLiteral("/base/data/a.nc"));
        const octrace::studio::StudioState defaults;
        QCOMPARE(s.depth, defaults.depth);
        QCOMPARE(s.renderer, defaults.renderer);
        QVERIFY(!s.iso && !s.cameraSet);
        // No background: the one contrasting with the surface, as render's default; kept unset.
        QVERIFY(!s.background && !octrace::studio::parseSession(octrace::studio::sessionJson(s)).background);
        QCOMPARE(octrace::studio::parseSession(octrace::studio::sessionJson(s)).input, s.input);
        const auto a = octrace::studio::parseSession(R"({"octrace_studio_session": 1, "input": {"path": "analytic:torus"}})", QStringLiteral("/base"));
        QCOMPARE(a.input, std::string("analytic:torus"));
        // A relief cut (the CLI's relief:FILE) is kept as typed; its file is read with the field.
        const auto r = octrace::studio::parseSession(
            R"({"octrace_studio_session": 1, "surface": {"cut": "relief:../shared/data/ocean/etopo20.cdf"}})");
        QCOMPARE(r.cut, std::string("relief:../shared/data/ocean/etopo20.cdf"));
        QCOMPARE(octrace::studio::parseSession(octrace::studio::sessionJson(r)).cut, r.cut);
        // Colours as a hand-written session may give them: the options table's names and hex.
        const auto c = octrace::studio::parseSession(
            "{\"octrace_studio_session\": 1, \"shading\": {\"colour\": \"tomato\", \"background\": \"#00000080\"}}");
        QCOMPARE(c.colour, octrace::vec3(1.0f, 99.0f / 255.0f, 71.0f / 255.0f));
        QVERIFY(c.background);
        QCOMPARE(*c.background, octrace::vec4(0.0f, 0.0f, 0.0f, 128.0f / 255.0f));
    }

    /// The widgets whose settings are in the options table, by key; the export dialog's are
    /// read while it is open.
    QMap<QString, QWidget*> optionWidgets(QWidget* root) {
        QMap<QString, QWidget*> found;
        for (QWidget* w : root->findChildren<QWidget*>()) {
            const QVariant key = w->property(octrace::studio::kOptionProperty);
            if (key.isValid()) found.insert(key.toString(), w);
        }
        return found;
    }

    /// Every numeric setting of the options table that the studio shows or saves, at its
    /// minimum, its maximum and just outside both: the widgets' ranges read back from the
    /// QSpinBox objects equal the table's (an open end one step inside), values past them are
    /// clamped; a session file takes the ends and refuses the values outside, naming the member.
    void optionTableRangesHoldInTheWidgetsAndSessions() {
        namespace model = octrace::model;
        // The export dialog's controls, read while it is open.
        QMap<QString, QPair<double, double>> dialogRanges;
        QVERIFY(runExportDialog([&](QDialog* dlg) {
            for (auto [key, w] : optionWidgets(dlg).asKeyValueRange())
                if (auto* box = qobject_cast<QSpinBox*>(w)) dialogRanges.insert(key, {double(box->minimum()), double(box->maximum())});
            dlg->reject();
        }));
        const QMap<QString, QWidget*> panel = optionWidgets(window_);
        int widgets = 0, sessions = 0;
        for (const model::Option* o : model::allOptions()) {
            if (o->kind != model::OptionKind::Integer && o->kind != model::OptionKind::Number) continue;
            const QString key = QString::fromLatin1(o->key);
            if (*o->label) {
                double lo = 0, hi = 0, step = 1;
                if (auto* box = qobject_cast<QSpinBox*>(panel.value(key))) {
                    const QSignalBlocker quiet(box);  // no rebuild at the probes
                    const int was = box->value();
                    const auto restore = qScopeGuard([&] { box->setValue(was); });
                    lo = box->minimum(), hi = box->maximum();
                    box->setValue(int(lo) - 1);
                    QCOMPARE(box->value(), int(lo));
                    box->setValue(int(hi) + 1);
                    QCOMPARE(box->value(), int(hi));
                } else if (auto* dbox = qobject_cast<QDoubleSpinBox*>(panel.value(key))) {
                    const QSignalBlocker quiet(dbox);
                    const double was = dbox->value();
                    const auto restore = qScopeGuard([&] { dbox->setValue(was); });
                    lo = dbox->minimum(), hi = dbox->maximum(), step = std::pow(10.0, -dbox->decimals());
                    dbox->setValue(lo - step);
                    QCOMPARE(dbox->value(), lo);
                    dbox->setValue(hi + step);
                    QCOMPARE(dbox->value(), hi);
                } else if (dialogRanges.contains(key)) {
                    lo = dialogRanges[key].first, hi = dialogRanges[key].second;
                } else {
                    QFAIL(qPrintable(QStringLiteral("no studio control for '%1' (label '%2')").arg(key, QLatin1String(o->label))));
                }
                // An unbounded end (`vertical_scale`'s maximum) is a spin box's largest value.
                constexpr double kUnboundedControl = 1e9;
                QVERIFY2(!std::isfinite(o->min) ? lo <= -kUnboundedControl
                         : o->minOpen           ? (lo > o->min && lo <= o->min + step)
                                                : lo == o->min,
                         qPrintable(key));
                QVERIFY2(!std::isfinite(o->max) ? hi >= kUnboundedControl
                         : o->maxOpen           ? (hi < o->max && hi >= o->max - step)
                                                : hi == o->max,
                         qPrintable(key));
                ++widgets;
            }
            if (*o->session) {
                const QString path = QString::fromLatin1(o->session);
                const QString group = path.section(QLatin1Char('.'), 0, 0), member = path.section(QLatin1Char('.'), 1);
                const auto session = [&](double v) {
                    return QStringLiteral(R"({"octrace_studio_session": 1, "%1": {"%2": %3}})").arg(group, member).arg(v, 0, 'g', 17).toUtf8();
                };
                const double inside = o->kind == model::OptionKind::Integer ? 1.0 : 1e-6;
                for (double v : {o->minOpen ? o->min + inside : o->min, o->maxOpen ? o->max - inside : o->max})
                    if (std::isfinite(v)) octrace::studio::parseSession(session(v));  // accepted: throws otherwise
                for (double v : {o->minOpen ? o->min : o->min - inside, o->maxOpen ? o->max : o->max + inside}) {
                    if (!std::isfinite(v)) continue;
                    try {
                        octrace::studio::parseSession(session(v));
                        QFAIL(qPrintable(QStringLiteral("%1 = %2 was accepted").arg(path).arg(v)));
                    } catch (const octrace::InputError& e) {
                        QVERIFY2(QString::fromStdString(e.what()).contains(path + QStringLiteral(": ")), e.what());
                    }
                }
                ++sessions;
            }
        }
        QVERIFY(widgets >= 9 && sessions >= 9);
    }

    void cleanupTestCase() { delete window_; }
};

QTEST_MAIN(StudioTest)
#include "StudioTest.moc"
