// QTest of the studio's ocean controls and step slider, driving the real window under Xvfb:
// region, depth range, vertical scale, sea floor and colour-by on the Levitus atlas give the
// image the CLI gives with the same options (pixel for pixel: the studio's export against
// `octrace render` of the command line it gives); the step slider reads a NetCDF time step or a
// volume of the XA10 4-D fMRI series as `--time N` / `--volume N` does, and Play advances.
// With OCTRACE_STUDIO_SCREENSHOTS=DIR set, screenshots of the window go to DIR.
#include "Engine.h"
#include "MainWindow.h"
#include "OceanPanel.h"
#include "RenderView.h"
#include "Session.h"
#include "SliceViews.h"
#include "StepSlider.h"

#include "octrace/util/Error.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QPlainTextEdit>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalSpy>
#include <QSlider>
#include <QSpinBox>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QToolButton>
#include <QtTest>

#include "StudioTestSupport.h"
#include "../ZarrStores.h"

using namespace octrace::studio::test;
using octrace::studio::Engine;
using octrace::studio::MainWindow;
using octrace::studio::OceanPanel;
using octrace::studio::StepSlider;

namespace {

const QString kLevitus = QStringLiteral(OCTRACE_SHARED_DATA "/ocean/levitus_climatology.cdf");
const QString kFmri = QStringLiteral(OCTRACE_SHARED_DATA "/medical/siemens_xa10_fmri_4d");

}  // namespace

class StudioOceanTest : public QObject {
    Q_OBJECT
private:
    MainWindow* window_ = nullptr;
    QTemporaryDir tmp_;
    QString screenshots_;
    int exports_ = 0;

    void screenshot(const QString& name) {
        if (!screenshots_.isEmpty()) QVERIFY(saveScreenshot(window_, tmp_.path(), screenshots_ + QLatin1Char('/') + name));
    }
    /// Opens `input` and waits for its first exact frame.
    void open(const QString& input) {
        // Built first: a frame of the input before (a change just made) may still be on its way.
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        QSignalSpy failed(&window_->engine(), &Engine::failed);
        window_->openInput(input);
        QVERIFY2(built.wait(kWaitMs), failed.isEmpty() ? "not built" : qPrintable(failed.first().first().toString()));
        QSignalSpy frames(window_, &MainWindow::frameShown);
        QVERIFY(frames.wait(kWaitMs));
    }
    /// Runs `change` and waits until its surface is built and drawn.
    void changeAndWait(const std::function<void()>& change) {
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        QSignalSpy failed(&window_->engine(), &Engine::failed);
        change();
        QVERIFY2(built.wait(kWaitMs), qPrintable(messages().right(600)));
        QVERIFY2(failed.isEmpty(), failed.isEmpty() ? "" : qPrintable(failed.first().first().toString()));
        QSignalSpy frames(window_, &MainWindow::frameShown);
        QVERIFY(frames.wait(kWaitMs));
    }
    /// Exports at width x height and renders the studio's own command line with the CLI: the
    /// two PNG files must be equal pixel for pixel. Returns the studio's file.
    QString exportEqualsCli(int width = 480, int height = 360) {
        const QString stem = tmp_.filePath(QStringLiteral("export%1").arg(++exports_));
        const QString studioPng = stem + QStringLiteral("-studio.png"), cliPng = stem + QStringLiteral("-cli.png");
        QSignalSpy exported(&window_->engine(), &Engine::exported);
        window_->exportFigure(studioPng, width, height, false);
        if (!exported.wait(kWaitMs)) return {};
        const QStringList args = window_->commandLine(cliPng, width, height);
        if (runCli(args) != 0) return {};
        const qint64 differing = differingPixels(studioPng, cliPng);
        if (differing != 0) {
            qWarning("%lld pixels differ from: octrace render %s", differing, qPrintable(args.join(' ')));
            return {};
        }
        const QImage img(studioPng);
        if (surfacePixels(img, img.pixel(0, 0)) < width * height / 50) return {};  // the surface is in the picture
        return studioPng;
    }
    QString messages() const {
        auto* m = window_->findChild<QPlainTextEdit*>();
        return m ? m->toPlainText() : QString();
    }
    template <class T>
    T* find(const char* name) const {
        return window_->findChild<T*>(QLatin1String(name));
    }
    OceanPanel* ocean() const { return window_->findChild<OceanPanel*>(); }
    StepSlider* steps() const { return window_->findChild<StepSlider*>(); }
    /// Writes the Levitus time series of tests/data/netcdf/make_levitus_seasons.py (too large to commit).
    QString seasons() {
        const QString out = tmp_.filePath(QStringLiteral("levitus_seasons.nc"));
        if (QFileInfo::exists(out)) return out;
        QProcess p;
        p.start(QStringLiteral(OCTRACE_TEST_PYTHON),
                {QStringLiteral(OCTRACE_TEST_DATA "/netcdf/make_levitus_seasons.py"), kLevitus, out});
        if (!p.waitForFinished(kWaitMs) || p.exitCode() != 0) {
            qWarning("make_levitus_seasons.py: %s", p.readAllStandardError().constData());
            return {};
        }
        return out;
    }

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QVERIFY(tmp_.isValid());
        if (!QFileInfo::exists(kLevitus)) QSKIP("the shared data (OCTRACE_SHARED_DATA) is absent");
        screenshots_ = qEnvironmentVariable("OCTRACE_STUDIO_SCREENSHOTS");
        window_ = new MainWindow;
        window_->resize(1200, 860);
        window_->show();
        QVERIFY(QTest::qWaitForWindowExposed(window_));
        // Small octrees: the comparisons do not need more, and the machine is shared.
        find<QSpinBox>("depthSpin")->setValue(6);
    }

    void oceanPanelShowsForGeographicFieldsOnly() {
        open(QStringLiteral(OCTRACE_SAMPLES "/torus.nrrd"));
        QVERIFY(!ocean()->isVisible());
        QVERIFY(!steps()->isVisible());  // one volume: nothing to step through
        open(QDir::current().relativeFilePath(kLevitus));  // as a user in the repository types it, for the screenshots
        QVERIFY(ocean()->isVisible());
        QVERIFY(!steps()->isVisible());  // the atlas is annual: no time axis
        // Without a region the boxes show what was read: the whole grid.
        QCOMPARE(find<QDoubleSpinBox>("regionWest")->value(), 20.5);
        QCOMPARE(find<QDoubleSpinBox>("regionEast")->value(), 379.5);
        QCOMPARE(find<QDoubleSpinBox>("regionSouth")->value(), -89.5);
        QCOMPARE(find<QDoubleSpinBox>("regionNorth")->value(), 89.5);
        QVERIFY(!find<QDoubleSpinBox>("regionWest")->isEnabled());
        QCOMPARE(find<QDoubleSpinBox>("depthTo")->value(), 5000.0);
        QVERIFY(find<QCheckBox>("verticalScaleAuto")->isChecked());
    }

    void regionAndDepthRangeGiveTheClisImage() {
        auto* iso = find<QDoubleSpinBox>("isoSpin");
        changeAndWait([&] { iso->setValue(10.0); });
        const auto whole = window_->engine().tree()->occupiedBounds();
        // The North Atlantic, as --region 280,360,0,65: the world is that box, framed anew.
        {
            const QSignalBlocker quiet(ocean());  // four boxes, then one read when the region is on
            find<QDoubleSpinBox>("regionWest")->setValue(280.0);
            find<QDoubleSpinBox>("regionEast")->setValue(360.0);
            find<QDoubleSpinBox>("regionSouth")->setValue(0.0);
            find<QDoubleSpinBox>("regionNorth")->setValue(65.0);
        }
        changeAndWait([&] { find<QCheckBox>("regionCheck")->setChecked(true); });
        QVERIFY(window_->commandLine(QStringLiteral("x.png"), 10, 10).join(' ').contains(QStringLiteral("--region 280,360,0,65")));
        const auto region = window_->engine().tree()->occupiedBounds();
        QVERIFY(region.hi.x - region.lo.x < 0.5 * (whole.hi.x - whole.lo.x));
        QCOMPARE(window_->engine().iso(), 10.0);  // the iso value stays
        QVERIFY(find<QDoubleSpinBox>("regionWest")->isEnabled());
        QVERIFY(!exportEqualsCli().isEmpty());
        // The upper 1000 m, as --depth-range 0,1000.
        {
            const QSignalBlocker quiet(ocean());
            find<QDoubleSpinBox>("depthFrom")->setValue(0.0);
            find<QDoubleSpinBox>("depthTo")->setValue(1000.0);
        }
        changeAndWait([&] { find<QCheckBox>("depthRangeCheck")->setChecked(true); });
        QVERIFY(window_->state().settings.at("depth_range") == "0,1000");
        QVERIFY(!exportEqualsCli().isEmpty());
    }

    void verticalScaleFloorAndColourByGiveTheClisImage() {
        // A vertical scale of its own, as --vertical-scale 1500 (the default makes the upper 1000 m a quarter of the width).
        {
            const QSignalBlocker quiet(ocean());
            find<QDoubleSpinBox>("vertical_scale")->setValue(1500.0);
        }
        changeAndWait([&] { find<QCheckBox>("verticalScaleAuto")->setChecked(false); });
        QCOMPARE(window_->state().settings.at("vertical_scale"), std::string("1500"));
        QVERIFY(!exportEqualsCli().isEmpty());
        // The sea floor and land under the surface (--floor): a build, not a read.
        QSignalSpy reads(&window_->engine(), &Engine::inputLoaded);
        changeAndWait([&] { find<QCheckBox>("floor")->setChecked(true); });
        QCOMPARE(reads.count(), 0);
        const QString floor = exportEqualsCli();
        QVERIFY(!floor.isEmpty());
        // Coloured by salinity (--colour-by SALT): the colour map of that variable.
        auto* colourBy = find<QComboBox>("colour_by");
        QVERIFY(colourBy->findText(QStringLiteral("SALT")) > 0);
        QCOMPARE(colourBy->findText(QStringLiteral("TEMP")), -1);  // the variable drawn is not offered
        changeAndWait([&] {
            colourBy->setCurrentIndex(colourBy->findText(QStringLiteral("SALT")));
            emit colourBy->activated(colourBy->currentIndex());
        });
        QVERIFY(window_->commandLine(QStringLiteral("x.png"), 10, 10).join(' ').contains(QStringLiteral("--colour-by SALT")));
        const QString salt = exportEqualsCli();
        QVERIFY(!salt.isEmpty());
        QVERIFY(differingPixels(floor, salt) > 1000);  // the colours changed
        // As a figure with its colour bar.
        window_->setFigure(true, QStringLiteral("Salinity on the 10 degC surface"), 100, true);
        QVERIFY(!exportEqualsCli(800, 600).isEmpty());
        window_->setFigure(false, QString(), 100, false);
    }

    void sessionKeepsTheOceanSettings() {
        const QString path = tmp_.filePath(QStringLiteral("ocean.json"));
        QVERIFY(window_->saveSessionTo(path));
        const auto s = octrace::studio::loadSession(path);
        QCOMPARE(s.settings, window_->state().settings);
        QCOMPARE(s.settings.at("floor"), std::string("on"));
        QCOMPARE(s.settings.at("colour_by"), std::string("SALT"));
        // A region the CLI refuses is refused in a session too, naming the member.
        try {
            octrace::studio::parseSession(R"({"octrace_studio_session": 1, "input": {"region": "0,10,50,40"}})");
            QFAIL("a region with LAT0 > LAT1 was accepted");
        } catch (const octrace::InputError& e) {
            QVERIFY2(QString::fromStdString(e.what()).startsWith(QStringLiteral("input.region: ")), e.what());
        }
    }

    void slicePanesCutAtADepthAndAlongSectionsAsTheCli() {
        // The four-up panes on the ocean field read (the North Atlantic, upper 1000 m): a map at
        // a depth (z) and sections along a parallel (y) and a meridian (x), each placed by its
        // position box as the CLI's --at, and drawn pixel for pixel as `octrace slice` draws the
        // pane's command line (which reads the same region and depths).
        auto* slices = window_->slices();
        slices->setFourUp(true);
        QTRY_VERIFY(slices->pane(0)->isVisible() && slices->pane(0)->hasSlice());
        QCOMPARE(slices->pane(0)->plane(), octrace::SlicePlane::Z);
        QCOMPARE(slices->pane(1)->plane(), octrace::SlicePlane::Y);
        QCOMPARE(slices->pane(2)->plane(), octrace::SlicePlane::X);
        auto* depth = find<QDoubleSpinBox>("sliceAt0");
        auto* latitude = find<QDoubleSpinBox>("sliceAt1");
        auto* longitude = find<QDoubleSpinBox>("sliceAt2");
        QVERIFY(depth && latitude && longitude && depth->isVisible());
        // The boxes span the grid read and half a step beyond (as --at takes it): the levels of
        // 0 .. 1000 m (the next one, 1200 m, is not read), 0 .. 65 N, 280 .. 360 E.
        const QString ranges = QStringLiteral("depth %1..%2, latitude %3..%4, longitude %5..%6")
                                   .arg(depth->minimum()).arg(depth->maximum()).arg(latitude->minimum()).arg(latitude->maximum())
                                   .arg(longitude->minimum()).arg(longitude->maximum());
        QVERIFY2(depth->minimum() <= 0.0 && depth->maximum() >= 1000.0 && depth->maximum() <= 1100.0, qPrintable(ranges));
        QVERIFY2(latitude->minimum() <= 0.5 && latitude->maximum() >= 64.5 && latitude->maximum() <= 65.5, qPrintable(ranges));
        QVERIFY2(longitude->minimum() <= 280.5 && longitude->maximum() >= 359.5, qPrintable(ranges));
        QVERIFY(depth->toolTip().contains(QStringLiteral("depth in metres")));  // the option's help
        // 450 m: between the levels of 400 and 500 m.
        depth->setValue(450.0);
        QVERIFY(slices->at(0) == 450.0);
        const QString command = slices->commandLine(0, QStringLiteral("x.png")).join(QLatin1Char(' '));
        QVERIFY2(command.contains(QStringLiteral("--plane z --at 450 ")), qPrintable(command));
        QVERIFY2(command.contains(QStringLiteral("--var TEMP")) && command.contains(QStringLiteral("--region 280,360,0,65")) &&
                     command.contains(QStringLiteral("--depth-range 0,1000")) && !command.contains(QStringLiteral("--floor")),
                 qPrintable(command));
        QVERIFY(slices->pane(0)->content().caption.contains(QStringLiteral("450 m depth")));
        QCOMPARE(paneDiffersFromCli(*slices, 0, tmp_.path(), QStringLiteral("depth450")), 0);
        const QImage at450 = slices->pane(0)->image();
        // A section along 30 N, and one along 30 W (330 E; the CLI takes -30 alike).
        latitude->setValue(30.0);
        QCOMPARE(paneDiffersFromCli(*slices, 1, tmp_.path(), QStringLiteral("lat30")), 0);
        longitude->setValue(330.0);
        QCOMPARE(paneDiffersFromCli(*slices, 2, tmp_.path(), QStringLiteral("lon330")), 0);
        QVERIFY(slices->at(0) == 450.0);  // placing the sections leaves the map at its depth
        QCOMPARE(slices->pane(0)->image(), at450);
        screenshot(QStringLiteral("studio-ocean-slices.png"));
        // The wheel goes on by samples from the nearest level: --index again.
        slices->step(0, 1);
        QVERIFY(!slices->at(0));
        QVERIFY(slices->commandLine(0, QStringLiteral("x.png")).contains(QStringLiteral("--index")));
        QCOMPARE(paneDiffersFromCli(*slices, 0, tmp_.path(), QStringLiteral("depthIndex")), 0);
        QVERIFY(slices->at(1) == 30.0 && slices->at(2) == 330.0);
        slices->setFourUp(false);
    }

    void aBadRegionIsRefusedAndTheFieldStays() {
        const std::string before = window_->state().settings.at("region");
        QSignalSpy reads(&window_->engine(), &Engine::inputLoaded);
        {
            const QSignalBlocker quiet(ocean());
            find<QDoubleSpinBox>("regionSouth")->setValue(70.0);  // the south edge north of the north edge
        }
        find<QDoubleSpinBox>("regionNorth")->setValue(10.0);  // 280,360,70,10: refused
        QCOMPARE(window_->state().settings.at("region"), before);
        QCOMPARE(reads.count(), 0);
        QCOMPARE(find<QDoubleSpinBox>("regionSouth")->value(), 0.0);  // the boxes show the region in use
        for (auto* box : window_->findChildren<QWidget*>(QStringLiteral("errorBox"))) box->close();
    }

    void engineKeepsOneCopyOfTheField() {
        // The slice panes' field is the one read, whose samples each build shares (no second
        // copy of the field beside the budget the read was checked against): a build, and
        // another after a new iso value, leave the samples where the read put them.
        Engine engine;
        octrace::studio::StudioState s;
        s.input = kLevitus.toStdString();
        s.variable = "TEMP";
        s.depth = 5;
        QSignalSpy built(&engine, &Engine::surfaceBuilt);
        engine.open(s);
        QVERIFY(built.wait(kWaitMs));
        const auto field = engine.field();
        QVERIFY(field && field->values.borrowed());
        const float* samples = field->values.data();
        const auto tree = engine.tree();
        s.iso = 12.0;
        engine.rebuild(s);
        QVERIFY(built.wait(kWaitMs));
        QVERIFY(engine.tree() != tree);  // built again, from the same samples
        QCOMPARE(engine.field(), field);
        QCOMPARE(engine.field()->values.data(), samples);
        QCOMPARE(engine.iso(), 12.0);
    }

    void timeSliderReadsTheStepAsTheCli() {
        const QString nc = seasons();
        QVERIFY(!nc.isEmpty());
        open(nc);
        QVERIFY(ocean()->isVisible());
        QVERIFY(steps()->isVisible());
        QCOMPARE(steps()->count(), 4);
        QCOMPARE(window_->findChild<QLabel*>(QStringLiteral("stepName"))->text(), QStringLiteral("step 0 of 4: 2001-01-15"));
        changeAndWait([&] { find<QDoubleSpinBox>("isoSpin")->setValue(20.0); });
        const QString january = exportEqualsCli();
        QVERIFY(!january.isEmpty());
        // July, by the slider: the time step read is the CLI's --time 2.
        changeAndWait([&] { find<QSlider>("stepSlider")->setValue(2); });
        QCOMPARE(window_->state().time, std::string("2"));
        QCOMPARE(window_->findChild<QLabel*>(QStringLiteral("stepName"))->text(), QStringLiteral("step 2 of 4: 2001-07-15"));
        QCOMPARE(window_->engine().iso(), 20.0);
        const QString july = exportEqualsCli();
        QVERIFY(!july.isEmpty());
        QVERIFY(differingPixels(january, july) > 1000);  // the warm water reaches further north in July
    }

    void cancellingAStepKeepsTheStepOnScreen() {
        const auto before = window_->engine().tree();
        QSignalSpy cancelled(&window_->engine(), &Engine::cancelled);
        find<QSlider>("stepSlider")->setValue(3);
        window_->engine().cancel();  // as the Cancel button (Esc) does, before the read is done
        QCOMPARE(cancelled.count(), 1);
        QCOMPARE(window_->engine().tree(), before);
        QCOMPARE(window_->state().time, std::string("2"));
        QCOMPARE(steps()->step(), 2);  // the slider shows the step on screen again
        QCOMPARE(window_->findChild<QLabel*>(QStringLiteral("stepName"))->text(), QStringLiteral("step 2 of 4: 2001-07-15"));
    }

    void playAdvancesThroughTheSteps() {
        QSignalSpy chosen(steps(), &StepSlider::stepChosen);
        find<QToolButton>("stepPlay")->click();
        QVERIFY(steps()->playing());
        // Each step is read and drawn before the next is asked for: 2 -> 3 -> 0 (looping).
        QTRY_VERIFY_WITH_TIMEOUT(chosen.count() >= 2, kWaitMs);
        QCOMPARE(chosen.at(0).first().toInt(), 3);
        QCOMPARE(chosen.at(1).first().toInt(), 0);
        find<QToolButton>("stepPlay")->click();
        QVERIFY(!steps()->playing());
        QTRY_VERIFY_WITH_TIMEOUT(!window_->engine().building(), kWaitMs);
        // Left on July for the picture: the subtropical gyre's upper 1000 m, over its sea floor.
        changeAndWait([&] { find<QSlider>("stepSlider")->setValue(2); });
        if (!screenshots_.isEmpty()) {
            {
                const QSignalBlocker quiet(ocean());
                find<QDoubleSpinBox>("regionWest")->setValue(280.0);
                find<QDoubleSpinBox>("regionEast")->setValue(345.0);
                find<QDoubleSpinBox>("regionSouth")->setValue(5.0);
                find<QDoubleSpinBox>("regionNorth")->setValue(55.0);
            }
            changeAndWait([&] { find<QCheckBox>("regionCheck")->setChecked(true); });
            {
                const QSignalBlocker quiet(ocean());
                find<QDoubleSpinBox>("depthFrom")->setValue(0.0);
                find<QDoubleSpinBox>("depthTo")->setValue(1000.0);
            }
            changeAndWait([&] { find<QCheckBox>("depthRangeCheck")->setChecked(true); });
            changeAndWait([&] { find<QCheckBox>("floor")->setChecked(true); });
            changeAndWait([&] { find<QSpinBox>("depthSpin")->setValue(8); });
            auto* colormap = find<QComboBox>("colormapCombo");
            colormap->setCurrentIndex(colormap->findText(QStringLiteral("viridis")));
            QSignalSpy frames(window_, &MainWindow::frameShown);
            QVERIFY(frames.wait(kWaitMs));
            screenshot(QStringLiteral("studio-ocean.png"));
            colormap->setCurrentIndex(0);
            changeAndWait([&] { find<QSpinBox>("depthSpin")->setValue(6); });
        }
    }

    void volumeSelectorReadsTheVolumeAsTheCli() {
        if (!QFileInfo::exists(kFmri)) QSKIP("the XA10 fMRI series is absent");
        open(QDir::current().relativeFilePath(kFmri));  // as a user in the repository types it, for the screenshot
        // The Series box counts one volume's slices, then the volumes (4 files of 6 frames).
        const QString seriesText = find<QComboBox>("seriesCombo")->currentText();
        QVERIFY2(seriesText.endsWith(QStringLiteral("(MR, 64x64x6, 4 volumes)")), qPrintable(seriesText));
        QVERIFY(!ocean()->isVisible());
        QVERIFY(steps()->isVisible());
        QCOMPARE(steps()->count(), 4);
        QCOMPARE(window_->findChild<QLabel*>(QStringLiteral("stepName"))->text(), QStringLiteral("volume 0 of 4: temporal position 1"));
        const QString first = exportEqualsCli();
        QVERIFY(!first.isEmpty());
        // Volume 3 by the index box: the CLI's --volume 3.
        changeAndWait([&] { find<QSpinBox>("stepIndex")->setValue(3); });
        QCOMPARE(window_->state().settings.at("volume"), std::string("3"));
        QVERIFY(window_->commandLine(QStringLiteral("x.png"), 10, 10).join(' ').contains(QStringLiteral("--volume 3")));
        QCOMPARE(window_->findChild<QLabel*>(QStringLiteral("stepName"))->text(), QStringLiteral("volume 3 of 4: temporal position 4"));
        const QString last = exportEqualsCli();
        QVERIFY(!last.isEmpty());
        QVERIFY(differingPixels(first, last) > 0);  // another time point, another surface
        // Cine: Play goes on from volume 3 to 0, 1, ...
        QSignalSpy chosen(steps(), &StepSlider::stepChosen);
        steps()->setPlaying(true);
        QTRY_VERIFY_WITH_TIMEOUT(chosen.count() >= 2, kWaitMs);
        QCOMPARE(chosen.at(0).first().toInt(), 0);
        QCOMPARE(chosen.at(1).first().toInt(), 1);
        steps()->setPlaying(false);
        QTRY_VERIFY_WITH_TIMEOUT(!window_->engine().building(), kWaitMs);
        changeAndWait([&] { find<QSpinBox>("stepIndex")->setValue(2); });
        QCOMPARE(window_->findChild<QLabel*>(QStringLiteral("stepName"))->text(), QStringLiteral("volume 2 of 4: temporal position 3"));
        if (!screenshots_.isEmpty()) {
            // The picture: volume 2 in the four-up layout, the volume selector in the Input box.
            auto* slices = window_->slices();
            slices->setFourUp(true);
            QTRY_VERIFY(slices->pane(0)->isVisible() && slices->pane(0)->hasSlice());
            // The 3-D view from a little above (the default looks at the 6-slice slab's edge).
            QSignalSpy frames(window_, &MainWindow::frameShown);
            for (int k = 0; k < 4; ++k) QTest::keyClick(window_->view(0), Qt::Key_Down);
            QTRY_VERIFY_WITH_TIMEOUT(!window_->engine().building() && frames.count() > 0, kWaitMs);
            window_->findChild<QScrollArea*>(QStringLiteral("sidePanel"))->verticalScrollBar()->setValue(0);
            screenshot(QStringLiteral("studio-volumes.png"));
            slices->setFourUp(false);
        }
    }

    void steppingTheVolumeKeepsTheSlicePanes() {
        // Cine over a 4-D series reads each volume anew; the grid stays, so the crosshair, the
        // panes' positions and the window stay too (they once went back to the middle and to the
        // automatic window at every volume), and each pane is the CLI's `slice --volume N`.
        if (!QFileInfo::exists(kFmri)) QSKIP("the XA10 fMRI series is absent");
        open(kFmri);
        auto* slices = window_->slices();
        slices->setFourUp(true);
        QTRY_VERIFY(slices->pane(0)->isVisible() && slices->pane(0)->hasSlice());
        const octrace::ivec3 dims = window_->engine().field()->dims;
        const octrace::ivec3 cursor(dims.x / 4, dims.y * 3 / 4, 1);
        QVERIFY(cursor != octrace::ivec3(dims.x / 2, dims.y / 2, dims.z / 2));  // not the default
        slices->setCursor(cursor);
        QVERIFY(slices->setWindowText("300,500"));  // a window of the user's own (as dragged)
        const std::string window = slices->windowText();
        QVERIFY(!window.empty());
        // The sagittal pane placed by its position box, between two samples.
        auto* sagittal = find<QDoubleSpinBox>("sliceAt2");
        QVERIFY(sagittal);
        const double at = 0.5 * (sagittal->minimum() + sagittal->maximum()) + 0.3;
        sagittal->setValue(at);
        QVERIFY(slices->at(2).has_value());
        const double atSet = *slices->at(2);
        const octrace::ivec3 kept = slices->cursor();
        for (int volume : {1, 3}) {
            changeAndWait([&] { find<QSpinBox>("stepIndex")->setValue(volume); });
            QCOMPARE(window_->state().settings.at("volume"), std::to_string(volume));
            QCOMPARE(slices->cursor(), kept);
            QVERIFY(slices->at(2) && *slices->at(2) == atSet);
            QCOMPARE(slices->windowText(), window);
            for (int i = 0; i < 3; ++i) {
                QVERIFY(slices->commandLine(i, QStringLiteral("x.png")).join(' ').contains(QStringLiteral("--volume %1").arg(volume)));
                QCOMPARE(paneDiffersFromCli(*slices, i, tmp_.path(), QStringLiteral("volume%1-pane%2").arg(volume).arg(i)), 0);
            }
        }
        // Another input (another grid) starts afresh: the middle and the automatic window.
        QSignalSpy built(&window_->engine(), &Engine::surfaceBuilt);
        window_->openInput(QStringLiteral(OCTRACE_SHARED_DATA "/medical/emri_small.dcm"));
        QVERIFY(built.wait(kWaitMs));
        const octrace::ivec3 other = window_->engine().field()->dims;
        QCOMPARE(slices->cursor(), octrace::ivec3(other.x / 2, other.y / 2, other.z / 2));
        QVERIFY(slices->windowText().empty());
        QVERIFY(!slices->at(2));
        slices->setFourUp(false);
    }

    void aZarrStoresMetadataFileOpensTheStore() {
        // The Open dialog picks files: a store's `.zgroup` given there, or dropped on the window,
        // opens the store's folder; File > Open Folder... opens folders.
        std::string why;
        bool unavailable = false;
        const std::string dir = octrace::test::zarrStores(kLevitus.toStdString(), why, unavailable);
        if (dir.empty() && unavailable) QSKIP(why.c_str());
        QVERIFY2(!dir.empty(), why.c_str());
        const std::string store = dir + "/levitus_gdal.zarr";
        open(QString::fromStdString(store + "/.zgroup"));
        QCOMPARE(window_->state().input, store);
        QCOMPARE(window_->windowTitle(), QStringLiteral("levitus_gdal.zarr - octrace studio"));
        bool folderAction = false;
        for (QAction* a : window_->findChildren<QAction*>())
            folderAction |= a->text() == QStringLiteral("Open &Folder...") && a->shortcut() == QKeySequence(QStringLiteral("Ctrl+Shift+O"));
        QVERIFY(folderAction);
    }

    void cleanupTestCase() { delete window_; }
};

QTEST_MAIN(StudioOceanTest)
#include "StudioOceanTest.moc"
