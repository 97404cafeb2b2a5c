#pragma once
// What the studio's QTests share: running the CLI on the command line the studio gives, and
// comparing PNG files pixel by pixel.
#include "SliceViews.h"

#include <QApplication>
#include <QImage>
#include <QLabel>
#include <QMainWindow>
#include <QPlainTextEdit>
#include <QProcess>
#include <QStatusBar>
#include <QString>
#include <QStringList>

namespace octrace::studio::test {

constexpr int kWaitMs = 60000;  // generous: a loaded CI machine; the steps take well under a second each

/// Runs `octrace COMMAND ARGS`; returns its exit code (stderr shown on failure).
inline int runOctrace(const QString& command, const QStringList& args) {
    QProcess p;
    p.setProgram(QStringLiteral(OCTRACE_BINARY));
    p.setArguments(QStringList{command} + args + QStringList{QStringLiteral("--quiet")});
    p.start();
    if (!p.waitForFinished(kWaitMs)) return -1;
    if (p.exitCode() != 0) qWarning("octrace %s: %s", qPrintable(command), p.readAllStandardError().constData());
    return p.exitCode();
}

/// Runs `octrace render ARGS`.
inline int runCli(const QStringList& args) { return runOctrace(QStringLiteral("render"), args); }

/// Runs `octrace slice ARGS`.
inline int runSlice(const QStringList& args) { return runOctrace(QStringLiteral("slice"), args); }

inline qint64 differingPixels(const QString& a, const QString& b);

/// Pane `i`'s image against the CLI's `slice` of the pane's own command line, both saved in
/// `folder` under `stem`: the number of differing pixels (-1: a size differs or the CLI failed).
inline qint64 paneDiffersFromCli(const SliceViews& slices, int i, const QString& folder, const QString& stem) {
    const QString studioPng = folder + QLatin1Char('/') + stem + QStringLiteral("-pane.png");
    const QString cliPng = folder + QLatin1Char('/') + stem + QStringLiteral("-cli.png");
    const QImage shown = slices.pane(i)->image();
    if (shown.size() != slices.pane(i)->imageSize() || !shown.save(studioPng)) return -1;
    const QStringList args = slices.commandLine(i, cliPng);
    if (runSlice(args) != 0) return -1;
    const qint64 n = differingPixels(studioPng, cliPng);
    if (n != 0) qWarning("%lld pixels differ from: octrace slice %s", n, qPrintable(args.join(' ')));
    return n;
}

/// Number of pixels whose RGBA differ (-1 when the sizes differ or a file is unreadable).
inline qint64 differingPixels(const QString& a, const QString& b) {
    QImage ia(a), ib(b);
    if (ia.isNull() || ib.isNull() || ia.size() != ib.size()) return -1;
    ia = ia.convertToFormat(QImage::Format_RGBA8888);
    ib = ib.convertToFormat(QImage::Format_RGBA8888);
    qint64 n = 0;
    for (int y = 0; y < ia.height(); ++y)
        for (int x = 0; x < ia.width(); ++x) n += ia.pixel(x, y) != ib.pixel(x, y);
    return n;
}

/// Pixels that are not the background's colour.
inline qint64 surfacePixels(const QImage& img, QRgb background) {
    qint64 n = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) n += (img.pixel(x, y) & 0xFFFFFF) != (background & 0xFFFFFF);
    return n;
}

/// Saves a picture of `window` as `file`. The lines about the test's own files (exports,
/// sessions in its scratch folder `scratch`) are left out of the pictures: a user's window names
/// their files.
inline bool saveScreenshot(QMainWindow* window, const QString& scratch, const QString& file) {
    if (auto* messages = window->findChild<QPlainTextEdit*>()) {
        QStringList lines = messages->toPlainText().split(QLatin1Char('\n'));
        lines.removeIf([&](const QString& l) { return l.contains(scratch); });
        messages->setPlainText(lines.join(QLatin1Char('\n')));
        messages->moveCursor(QTextCursor::End);
        messages->ensureCursorVisible();
    }
    for (auto* label : window->statusBar()->findChildren<QLabel*>())
        if (label->text().contains(scratch)) label->clear();
    // An input made in the scratch folder (the Input panel's label): its file name.
    for (auto* label : window->findChildren<QLabel*>())
        if (label->text().contains(scratch)) label->setText(label->text().remove(scratch + QLatin1Char('/')));
    QApplication::processEvents();  // the labels' layout settles (a label changed just now, its room)
    return window->grab().save(file);
}

}  // namespace octrace::studio::test
