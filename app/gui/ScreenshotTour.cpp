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

namespace {

/// Screenshot mode: a whole run and a run over seeds 1-10, then each tab as a person sees it;
/// then, if a seed lost an active trial, that seed's run with the replay on the lost trial.
class ScreenshotTour {
public:
    ScreenshotTour(MainWindow& window, const QString& dir)
        : window_(window),
          dir_(dir),
          // Beside the paper, its kernel variant for the comparison tab, if it is there.
          kernel_(QFileInfo(window.experimentPath()).dir().filePath("paper_kernel.json")) {}

    int run() {
        // The window fills the screen's free area, as a maximised window does.
        if (QScreen* screen = window_.screen()) window_.setGeometry(screen->availableGeometry());
        QDir().mkpath(dir_);
        window_.setOutputBase(QDir(dir_).filePath("runs"));
        window_.setPace(Pace::Fastest);
        // The scene first, whichever panel the saved layout last showed in the left dock.
        raiseDock("sceneDock");
        QObject::connect(&window_, &MainWindow::runEnded, &window_,
                         [this](bool completed) { runEnded(completed); });
        later(200, [this] { return window_.startRun(RunController::What::Everything); });
        QApplication::exec();
        return status_;
    }

private:
    /// `start` after `ms`; the tour ends with status 1 where it does not start.
    template <typename Start>
    void later(int ms, Start start) {
        QTimer::singleShot(ms, &window_, [start] {
            if (!start()) QApplication::exit(1);
        });
    }
    bool raiseDock(const char* name) {
        auto* dock = window_.findChild<QDockWidget*>(name);
        if (dock) dock->raise();
        return dock != nullptr;
    }
    static void settle() {
        QApplication::processEvents();
        QEventLoop wait;
        QTimer::singleShot(300, &wait, &QEventLoop::quit);
        wait.exec();
    }
    void save(int number, const QString& name) {
        settle();
        window_.grab().save(QDir(dir_).filePath(QString("%1_%2.png").arg(number).arg(name)));
    }
    /// The whole screen as a person sees it: the window, fitted to it, with its status bar.
    void saveScreen(const QString& name) {
        settle();
        if (QScreen* screen = window_.screen())
            screen->grabWindow(0).save(QDir(dir_).filePath(name + ".png"));
    }

    void runEnded(bool completed) {
        const int step = ++runsEnded_;
        if (!completed) status_ = 1;
        if (step == 1 && completed) return later(200, [this] { return window_.startSeeds(1, 10); });
        if (step == 2 && completed && !compared_ && QFileInfo::exists(kernel_)) {
            compared_ = true;
            return later(200, [this] { return window_.startComparison(kernel_, 1, 10); });
        }
        if (step == 3 && completed && compared_ && !paired_) {
            paired_ = true;
            if (startLostPair()) return;
        }
        QTimer::singleShot(500, &window_, [this, completed] {
            if (replaying_)
                saveReplay();
            else
                saveEveryView(completed);
        });
    }

    /// The first active trial one of the two lost, in both (or else the first active trial they
    /// ended differently), replayed as a pair; false where there is none.
    bool startLostPair() {
        QTableWidget* rows = window_.comparisonTab()->table();
        int shown = -1, firstActive = -1;
        for (int r = 0; r < rows->rowCount() && shown < 0; ++r) {
            if (rows->item(r, 1)->text() != "active") continue;
            if (firstActive < 0) firstActive = r;
            if (rows->item(r, 4)->text().startsWith("lost") ||
                rows->item(r, 5)->text().startsWith("lost"))
                shown = r;
        }
        if (shown < 0) shown = firstActive;
        if (shown < 0) return false;
        rows->selectRow(shown);
        later(200, [this, shown] {
            QTableWidget* t = window_.comparisonTab()->table();
            return window_.startTrialPair(t->item(shown, 0)->text().toULongLong(),
                                          FollowingMode::Active, t->item(shown, 2)->text(),
                                          t->item(shown, 3)->text().toInt());
        });
        return true;
    }

    /// The seed's run: its trials and the replay of the first lost active trial.
    void saveReplay() {
        raiseDock("sceneDock");
        window_.tabs()->setCurrentWidget(window_.followingTab());
        if (auto* views = window_.followingTab()->findChild<QTabWidget*>())
            views->setCurrentIndex(views->count() - 1);
        save(window_.tabs()->count() + 3, "lost_trial_replay");
        QApplication::quit();
    }

    /// The screen, every tab, the devices and the protocol; then the seed that lost a trial.
    void saveEveryView(bool completed) {
        const int tabs = window_.tabs()->count();
        // The whole screen on the paths the run traced: the window as it opens on a laptop.
        window_.tabs()->setCurrentWidget(window_.followingTab());
        saveScreen(QString("0_screen_%1x%2")
                       .arg(window_.screen()->size().width())
                       .arg(window_.screen()->size().height()));
        for (int i = 0; i < tabs; ++i) {
            window_.tabs()->setCurrentIndex(i);
            save(i + 1,
                 window_.tabs()->tabText(i).replace("&&", "and").replace(' ', '_').toLower());
        }
        // The device panels share the left dock with the scene: raise them for one more; and the
        // protocol panel, the experiment's settings beside the scene.
        if (raiseDock("devicesDock")) save(tabs + 1, "devices");
        if (raiseDock("protocolDock")) save(tabs + 2, "protocol");
        const std::optional<std::uint64_t> lost =
            completed ? window_.seedsTab()->firstSeedWithLostActiveTrial() : std::nullopt;
        replaying_ = true;
        if (!lost || !window_.startSeedRun(*lost)) QApplication::quit();
    }

    MainWindow& window_;
    const QString dir_, kernel_;
    int status_ = 0, runsEnded_ = 0;
    bool compared_ = false, paired_ = false, replaying_ = false;
};

}  // namespace

int runScreenshotTour(MainWindow& window, const QString& dir) {
    return ScreenshotTour(window, dir).run();
}

}  // namespace activetouch
