#include "app/gui/ScreenshotTour.h"

#include <QApplication>
#include <QDir>
#include <QDockWidget>
#include <QEventLoop>
#include <QFileInfo>
#include <QScreen>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>

#include "app/gui/ComparisonTab.h"
#include "app/gui/FollowingTab.h"
#include "app/gui/MainWindow.h"
#include "app/gui/SeedsTab.h"

namespace activetouch {

int runScreenshotTour(MainWindow& window, const QString& dir) {
    // The window fills the screen's free area, as a maximised window does.
    if (QScreen* screen = window.screen()) window.setGeometry(screen->availableGeometry());
    // Screenshot mode: a whole run and a run over seeds 1-10, then each tab as a person sees it;
    // then, if a seed lost an active trial, that seed's run with the replay on the lost trial.
    QDir().mkpath(dir);
    window.setOutputBase(QDir(dir).filePath("runs"));
    window.setPace(Pace::Fastest);
    // The scene first, whichever panel the saved layout last showed in the left dock.
    if (auto* scene = window.findChild<QDockWidget*>("sceneDock")) scene->raise();
    auto settle = [] {
        QApplication::processEvents();
        QEventLoop wait;
        QTimer::singleShot(300, &wait, &QEventLoop::quit);
        wait.exec();
    };
    auto save = [&](int number, const QString& name) {
        window.grab().save(QDir(dir).filePath(QString("%1_%2.png").arg(number).arg(name)));
    };
    // The whole screen as a person sees it: the window, fitted to it, with its status bar.
    auto saveScreen = [&](const QString& name) {
        if (QScreen* screen = window.screen())
            screen->grabWindow(0).save(QDir(dir).filePath(name + ".png"));
    };
    int status = 0, runsEnded = 0;
    bool compared = false, paired = false, replaying = false;
    // Beside the paper, its kernel variant for the comparison tab, if it is there.
    const QString kernel = QFileInfo(window.experimentPath()).dir().filePath("paper_kernel.json");
    QObject::connect(&window, &MainWindow::runEnded, &window, [&](bool completed) {
        const int step = ++runsEnded;
        if (!completed) status = 1;
        if (step == 1 && completed) {
            QTimer::singleShot(200, &window, [&] {
                if (!window.startSeeds(1, 10)) QApplication::exit(1);
            });
            return;
        }
        if (step == 2 && completed && !compared && QFileInfo::exists(kernel)) {
            compared = true;
            QTimer::singleShot(200, &window, [&] {
                if (!window.startComparison(kernel, 1, 10)) QApplication::exit(1);
            });
            return;
        }
        if (step == 3 && completed && compared && !paired) {
            // The first active trial one of the two lost, in both (or else the first active
            // trial they ended differently).
            paired = true;
            QTableWidget* rows = window.comparisonTab()->table();
            int shown = -1, firstActive = -1;
            for (int r = 0; r < rows->rowCount() && shown < 0; ++r) {
                if (rows->item(r, 1)->text() != "active") continue;
                if (firstActive < 0) firstActive = r;
                if (rows->item(r, 4)->text().startsWith("lost") ||
                    rows->item(r, 5)->text().startsWith("lost"))
                    shown = r;
            }
            if (shown < 0) shown = firstActive;
            if (shown >= 0) {
                rows->selectRow(shown);
                QTimer::singleShot(200, &window, [&, shown] {
                    QTableWidget* t = window.comparisonTab()->table();
                    if (!window.startTrialPair(t->item(shown, 0)->text().toULongLong(),
                                               FollowingMode::Active, t->item(shown, 2)->text(),
                                               t->item(shown, 3)->text().toInt()))
                        QApplication::exit(1);
                });
                return;
            }
        }
        QTimer::singleShot(500, &window, [&, completed] {
            const int tabs = window.tabs()->count();
            if (replaying) {
                // The seed's run: its trials and the replay of the first lost active trial.
                if (auto* scene = window.findChild<QDockWidget*>("sceneDock")) scene->raise();
                window.tabs()->setCurrentWidget(window.followingTab());
                if (auto* views = window.followingTab()->findChild<QTabWidget*>())
                    views->setCurrentIndex(views->count() - 1);
                settle();
                save(tabs + 3, "lost_trial_replay");
                QApplication::quit();
                return;
            }
            // The whole screen on the paths the run traced: the window as it opens on a laptop.
            window.tabs()->setCurrentWidget(window.followingTab());
            settle();
            saveScreen(QString("0_screen_%1x%2")
                           .arg(window.screen()->size().width())
                           .arg(window.screen()->size().height()));
            for (int i = 0; i < tabs; ++i) {
                window.tabs()->setCurrentIndex(i);
                settle();
                save(i + 1,
                     window.tabs()->tabText(i).replace("&&", "and").replace(' ', '_').toLower());
            }
            // The device panels share the left dock with the scene: raise them for one more.
            if (auto* devices = window.findChild<QDockWidget*>("devicesDock")) {
                devices->raise();
                settle();
                save(tabs + 1, "devices");
            }
            // And the protocol panel, the experiment's settings beside the scene.
            if (auto* protocol = window.findChild<QDockWidget*>("protocolDock")) {
                protocol->raise();
                settle();
                save(tabs + 2, "protocol");
            }
            const std::optional<std::uint64_t> lost =
                completed ? window.seedsTab()->firstSeedWithLostActiveTrial() : std::nullopt;
            replaying = true;
            if (!lost || !window.startSeedRun(*lost)) QApplication::quit();
        });
    });
    QTimer::singleShot(200, &window, [&] {
        if (!window.startRun(RunController::What::Everything)) QApplication::exit(1);
    });
    QApplication::exec();
    return status;
}

}  // namespace activetouch
