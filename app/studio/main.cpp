// octrace-studio: the Qt application. `octrace-studio [INPUT]` opens INPUT (any input of the
// octrace CLI) at start.
#include "MainWindow.h"

#include <QApplication>
#include <QCommandLineParser>

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("octrace-studio"));
    QApplication::setOrganizationName(QStringLiteral("octrace"));
    QApplication::setApplicationVersion(QStringLiteral(OCTRACE_VERSION));
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral("octrace studio: interactive octree ray casting of scientific volumes"));
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addPositionalArgument(QStringLiteral("INPUT"), QStringLiteral("input to open (a file, a DICOM folder, analytic:NAME)"));
    parser.process(app);
    octrace::studio::MainWindow window;
    window.show();
    if (!parser.positionalArguments().isEmpty()) window.openInput(parser.positionalArguments().first());
    return app.exec();
}
