// activetouch: the workbench window.
//   activetouch [experiment.json]
//   activetouch --screenshots <dir> [experiment.json]   the screenshot tour (ScreenshotTour.h)
#include <QApplication>
#include <QCommandLineParser>
#include <QDir>
#include <QSettings>
#include <cstdio>
#include <cstring>
#include <memory>

#include "app/figures/Installation.h"
#include "app/gui/MainWindow.h"
#include "app/gui/ScreenshotTour.h"
#include "core/common/HeapTuning.h"

using namespace activetouch;

int main(int argc, char** argv) {
    keepHeapBetweenRuns();  // the window runs sweeps over seeds as the command line does
    // --help and --version print and quit: they need no display.
    bool textOnly = false;
    for (int i = 1; i < argc; ++i)
        for (const char* option : {"--help", "-h", "--help-all", "--version", "-v"})
            textOnly = textOnly || std::strcmp(argv[i], option) == 0;
    for (int i = 1; i < argc; ++i)
        if (std::strcmp(argv[i], "--version") == 0 || std::strcmp(argv[i], "-v") == 0) {
            std::printf("activetouch %s\n", ACTIVETOUCH_VERSION);  // as activetouch-cli says it
            return 0;
        }
    std::unique_ptr<QCoreApplication> application =
        textOnly ? std::make_unique<QCoreApplication>(argc, argv)
                 : std::make_unique<QApplication>(argc, argv);
    QCoreApplication& app = *application;
    QCoreApplication::setOrganizationName("ActiveTouch");
    QCoreApplication::setApplicationName("Workbench");
    QCoreApplication::setApplicationVersion(ACTIVETOUCH_VERSION);
    if (!textOnly) QGuiApplication::setDesktopFileName("activetouch");
    useInstalledResources();
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "ActiveTouch Workbench: active tactile perception experiments on a simulated or real rig.");
    parser.addHelpOption();
    parser.addVersionOption();
    QCommandLineOption shots("screenshots",
                             "Run the experiment, then over seeds 1-10, then compare it with "
                             "paper_kernel.json beside it (if there) over seeds 1-10, save a "
                             "screenshot of the screen and of each tab into <dir>, and of the "
                             "replay of the first lost active trial over those seeds, and quit. "
                             "Reads and keeps no settings of its own.",
                             "dir");
    parser.addOption(shots);
    parser.addPositionalArgument(
        "experiment",
        "Experiment file to open (default: the last one, or the shipped paper.json).");
    parser.process(app);

    if (parser.isSet(shots)) {
        // The tour starts from the defaults and leaves the user's settings as they were.
        const QString dir = parser.value(shots);
        QSettings::setDefaultFormat(QSettings::IniFormat);
        QSettings::setPath(QSettings::IniFormat, QSettings::UserScope,
                           QDir(dir).filePath("settings"));
        QDir(QDir(dir).filePath("settings")).removeRecursively();
    }
    MainWindow window;
    if (!parser.positionalArguments().isEmpty() &&
        !window.openExperiment(parser.positionalArguments().front())) {
        if (parser.isSet(shots)) return 2;
    }
    window.show();
    if (!parser.isSet(shots)) return app.exec();
    return runScreenshotTour(window, parser.value(shots));
}
