// activetouch: the workbench window.
//   activetouch [experiment.json]
//   activetouch --screenshots <dir> [experiment.json]   run the experiment, then over seeds 1-10,
//   save a PNG of each tab and of the device panels, quit
#include <QApplication>
#include <QCommandLineParser>
#include <QDir>
#include <QDockWidget>
#include <QTabWidget>
#include <QTimer>

#include "app/gui/MainWindow.h"

using namespace activetouch;

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    QApplication::setOrganizationName("ActiveTouch");
    QApplication::setApplicationName("Workbench");
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "ActiveTouch Workbench: active tactile perception experiments on a simulated or real rig.");
    parser.addHelpOption();
    QCommandLineOption shots("screenshots",
                             "Run the experiment, then over seeds 1-10, save a screenshot of each "
                             "tab into <dir>, and quit.",
                             "dir");
    parser.addOption(shots);
    parser.addPositionalArgument(
        "experiment",
        "Experiment file to open (default: the last one, or experiments/paper.json).");
    parser.process(app);

    MainWindow window;
    if (!parser.positionalArguments().isEmpty() &&
        !window.openExperiment(parser.positionalArguments().front())) {
        if (parser.isSet(shots)) return 2;
    }
    window.resize(1700, 1050);
    window.show();
    if (!parser.isSet(shots)) return app.exec();

    // Screenshot mode: a whole run and a run over seeds 1-10, then each tab as a person sees it.
    const QString dir = parser.value(shots);
    QDir().mkpath(dir);
    window.setOutputBase(QDir(dir).filePath("runs"));
    window.setPace(Pace::Fastest);
    // The scene first, whichever panel the saved layout last showed in the left dock.
    if (auto* scene = window.findChild<QDockWidget*>("sceneDock")) scene->raise();
    int status = 0, runsEnded = 0;
    QObject::connect(&window, &MainWindow::runEnded, &window, [&](bool completed) {
        if (++runsEnded == 1 && completed) {
            QTimer::singleShot(200, &window, [&] {
                if (!window.startSeeds(1, 10)) app.exit(1);
            });
            return;
        }
        QTimer::singleShot(500, &window, [&, completed] {
            for (int i = 0; i < window.tabs()->count(); ++i) {
                window.tabs()->setCurrentIndex(i);
                QApplication::processEvents();
                QTimer t;
                QEventLoop wait;
                QTimer::singleShot(300, &wait, &QEventLoop::quit);
                wait.exec();
                const QString name =
                    window.tabs()->tabText(i).replace("&&", "and").replace(' ', '_').toLower();
                window.grab().save(QDir(dir).filePath(QString("%1_%2.png").arg(i + 1).arg(name)));
            }
            // The device panels share the left dock with the scene: raise them for one more.
            if (auto* devices = window.findChild<QDockWidget*>("devicesDock")) {
                devices->raise();
                QApplication::processEvents();
                window.grab().save(
                    QDir(dir).filePath(QString("%1_devices.png").arg(window.tabs()->count() + 1)));
            }
            status = completed ? 0 : 1;
            app.quit();
        });
    });
    QTimer::singleShot(200, &window, [&] {
        if (!window.startRun(RunController::What::Everything)) app.exit(1);
    });
    app.exec();
    return status;
}
