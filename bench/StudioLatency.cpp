// octrace_studio_latency: the studio's input-to-paint latency while orbiting (issue 23), for
// bench/studio_latency.py. Opens INPUT in the real window (MainWindow), sets the iso value, depth
// and renderer through its controls, sizes the main view to the asked size, then orbits: a left
// button press in the view, mouse moves posted to the event queue every --interval-ms (as a
// window system delivers them), a release; --rounds times. The window measures each input's
// latency itself (LatencyMeter.h: from the event's handling to the end of the paint of the first
// frame showing it); this tool only drives the window and writes what it measured as JSON.
//
// Usage: octrace_studio_latency INPUT --iso V --depth D --renderer NAME --size WxH
//            [--moves N] [--step-px P] [--interval-ms T] [--rounds R] [--screenshot FILE.png] --out FILE.json
#include "MainWindow.h"
#include "RenderView.h"

#include <QApplication>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QMouseEvent>
#include <QSpinBox>
#include <QThread>
#include <QTimer>

#include <cstdio>
#include <functional>
#include <thread>

using octrace::studio::FrameResult;
using octrace::studio::LatencyMeter;
using octrace::studio::MainWindow;
using octrace::studio::RenderView;

namespace {

[[noreturn]] void fail(const QString& what) {
    std::fprintf(stderr, "octrace_studio_latency: %s\n", qPrintable(what));
    std::exit(1);
}

/// Runs the event loop until `done()` holds (checked every 5 ms); fails after `timeoutMs`.
void waitUntil(const std::function<bool()>& done, int timeoutMs, const QString& what) {
    QElapsedTimer t;
    t.start();
    while (!done()) {
        if (t.elapsed() > timeoutMs) fail("timed out waiting for " + what);
        QEventLoop loop;
        QTimer::singleShot(5, &loop, &QEventLoop::quit);
        loop.exec();
    }
}

void postMouse(RenderView* view, QEvent::Type type, QPoint at, Qt::MouseButton button, Qt::MouseButtons buttons) {
    QCoreApplication::postEvent(view, new QMouseEvent(type, QPointF(at), view->mapToGlobal(QPointF(at)), button, buttons,
                                                      Qt::NoModifier));
}

}  // namespace

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    const QStringList args = QApplication::arguments();
    QString input, renderer = QStringLiteral("full"), out, screenshot;
    double iso = 0.0;
    int depth = 9, moves = 120, stepPx = 4, intervalMs = 16, rounds = 3, width = 1280, height = 800;
    bool isoSet = false;
    for (int i = 1; i < args.size(); ++i) {
        const QString& a = args[i];
        auto next = [&] {
            if (i + 1 >= args.size()) fail(a + " needs a value");
            return args[++i];
        };
        if (a == QLatin1String("--iso")) iso = next().toDouble(&isoSet);
        else if (a == QLatin1String("--depth")) depth = next().toInt();
        else if (a == QLatin1String("--renderer")) renderer = next();
        else if (a == QLatin1String("--moves")) moves = next().toInt();
        else if (a == QLatin1String("--step-px")) stepPx = next().toInt();
        else if (a == QLatin1String("--interval-ms")) intervalMs = next().toInt();
        else if (a == QLatin1String("--rounds")) rounds = next().toInt();
        else if (a == QLatin1String("--out")) out = next();
        else if (a == QLatin1String("--screenshot")) screenshot = next();
        else if (a == QLatin1String("--size")) {
            const QStringList wh = next().split(QLatin1Char('x'));
            if (wh.size() != 2) fail("--size WxH");
            width = wh[0].toInt();
            height = wh[1].toInt();
        } else if (a.startsWith(QLatin1String("--"))) fail("unknown option " + a);
        else input = a;
    }
    if (input.isEmpty() || out.isEmpty() || !isoSet) fail("usage: INPUT --iso V --depth D --renderer NAME --size WxH --out FILE");

    MainWindow w;
    w.resize(width + 420, height + 260);
    w.show();
    auto* view = w.view(0);
    auto* depthSpin = w.findChild<QSpinBox*>(QStringLiteral("depthSpin"));
    auto* isoSpin = w.findChild<QDoubleSpinBox*>(QStringLiteral("isoSpin"));
    auto* rendererCombo = w.findChild<QComboBox*>(QStringLiteral("rendererCombo"));
    if (!depthSpin || !isoSpin || !rendererCombo) fail("the window's controls are not found");
    QString failure;
    QObject::connect(&w.engine(), &octrace::studio::Engine::failed, [&](const QString& m) { failure = m; });
    int built = 0;
    QObject::connect(&w.engine(), &octrace::studio::Engine::surfaceBuilt, [&] { ++built; });
    depthSpin->setValue(depth);
    w.openInput(input);
    waitUntil([&] { return built > 0 || !failure.isEmpty(); }, 600000, "the input to be read");
    if (!failure.isEmpty()) fail(failure);
    isoSpin->setValue(iso);
    waitUntil([&] { return !failure.isEmpty() || (w.engine().depth() == depth && std::abs(w.engine().iso() - iso) < 1e-9 && !w.engine().building()); },
              600000, "the surface at the asked iso value and depth");
    if (!failure.isEmpty()) fail(failure);
    if (rendererCombo->findText(renderer) < 0) fail("no renderer " + renderer + " in the studio");
    rendererCombo->setCurrentText(renderer);
    for (int tries = 0; tries < 10 && view->size() != QSize(width, height); ++tries) {
        w.resize(w.size() + QSize(width, height) - view->size());
        QApplication::processEvents();
        QThread::msleep(50);
        QApplication::processEvents();
    }
    if (view->size() != QSize(width, height))
        fail(QStringLiteral("the main view is %1x%2, not %3x%4 (screen too small?)").arg(view->width()).arg(view->height()).arg(width).arg(height));

    // Every frame rendered, for the record: preview or exact, its size and render time.
    QJsonArray frames;
    bool recording = false;
    QObject::connect(&w.engine(), &octrace::studio::Engine::frameReady, [&](const FrameResult& r) {
        if (!recording || r.panes.empty()) return;
        frames.append(QJsonObject{{"preview", r.preview}, {"width", r.panes[0].frame.width}, {"height", r.panes[0].frame.height},
                                  {"render_ms", r.panes[0].stats.renderMs}, {"level", r.level},
                                  {"renderer", QString::fromStdString(r.panes[0].stats.renderer)}});
    });
    // The first exact frame at the view's size.
    bool exactShown = false;
    QObject::connect(&w, &MainWindow::frameShown, [&] { exactShown = true; });
    waitUntil([&] { return !failure.isEmpty() || (view->image().size() == QSize(width, height) && exactShown && !w.engine().building()); },
              120000, "the first exact frame");
    // Idle: painted, and no frame request left over.
    QEventLoop idle;
    QTimer::singleShot(1000, &idle, &QEventLoop::quit);
    idle.exec();
    w.latency().clear();
    recording = true;

    const QPoint centre = view->rect().center();
    for (int round = 0; round < rounds; ++round) {
        QPoint at = centre - QPoint(moves * stepPx / 2, 0);
        postMouse(view, QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton);
        // The moves from a precise timer, the GUI thread idle in its event loop between them (as
        // under a real mouse); a tick that comes late, the GUI thread being busy, posts late.
        QTimer ticks;
        ticks.setTimerType(Qt::PreciseTimer);
        ticks.setInterval(intervalMs);
        QEventLoop orbit;
        int m = 0;
        QObject::connect(&ticks, &QTimer::timeout, [&] {
            at += QPoint(stepPx, 0);
            postMouse(view, QEvent::MouseMove, at, Qt::NoButton, Qt::LeftButton);
            if (++m == moves) {
                ticks.stop();
                postMouse(view, QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton);
                orbit.quit();
            }
        });
        ticks.start();
        orbit.exec();
        waitUntil([&] {
            const auto& s = w.latency().samples();
            return !failure.isEmpty() || (w.latency().unanswered() == 0 && !s.empty() && s.back().input == LatencyMeter::Input::Finish);
        }, 120000, "the exact frame after the release");
        if (!failure.isEmpty()) fail(failure);
        QEventLoop pause;
        QTimer::singleShot(500, &pause, &QEventLoop::quit);
        pause.exec();
    }

    if (!screenshot.isEmpty() && !w.grab().save(screenshot)) fail("cannot write " + screenshot);
    QJsonArray samples;
    for (const auto& s : w.latency().samples())
        samples.append(QJsonObject{{"input", s.input == LatencyMeter::Input::Move ? "move" : "release"}, {"preview", s.preview}, {"ms", s.ms}});
    const QJsonObject doc{{"input", input}, {"iso", iso}, {"depth", w.engine().depth()}, {"renderer", renderer},
                          {"view", QStringLiteral("%1x%2").arg(view->width()).arg(view->height())},
                          {"device_pixel_ratio", view->devicePixelRatioF()},
                          {"threads", int(std::thread::hardware_concurrency())},
                          {"boundary_voxels", qint64(w.engine().tree()->boundaryVoxels())},
                          {"moves_per_round", moves}, {"step_px", stepPx}, {"interval_ms", intervalMs}, {"rounds", rounds},
                          {"samples", samples}, {"frames", frames}};
    QFile f(out);
    if (!f.open(QIODevice::WriteOnly)) fail("cannot write " + out);
    f.write(QJsonDocument(doc).toJson());
    return 0;
}
