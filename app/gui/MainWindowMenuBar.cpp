// The window's menu bar: File, Run, View and Help, with their shortcuts (docs/window.md).
#include <QAction>
#include <QDockWidget>
#include <QFileDialog>
#include <QMenuBar>
#include <QMessageBox>
#include <QTabWidget>
#include <QToolBar>

#include "app/gui/ComparisonTab.h"
#include "app/gui/DevicesPanel.h"
#include "app/gui/LiveView.h"
#include "app/gui/MainWindow.h"
#include "app/gui/SeedsTab.h"

namespace activetouch {

namespace {

/// The platform's key sequence for `key`, or `fallback` where the platform has none.
QKeySequence standardOr(QKeySequence::StandardKey key, const QKeySequence& fallback) {
    const QList<QKeySequence> keys = QKeySequence::keyBindings(key);
    return keys.isEmpty() ? fallback : keys.front();
}

/// An action in `menu` that calls `slot` on `window`, with its shortcut and object name (by which
/// tests find it).
template <typename Slot>
QAction* addMenuAction(MainWindow* window, QMenu* menu, const QString& text,
                       const QKeySequence& keys, Slot slot, const char* name) {
    QAction* a = menu->addAction(text, window, slot);
    a->setShortcut(keys);
    a->setObjectName(name);
    return a;
}

/// One of the window's own actions put in `menu`, with its shortcut.
void addWithShortcut(QMenu* menu, QAction* action, const QKeySequence& keys) {
    menu->addAction(action);
    action->setShortcut(keys);
}

}  // namespace

void MainWindow::buildMenus() {
    buildFileMenu();
    buildRunMenu();
    buildViewMenu();
    buildHelpMenu();
}

void MainWindow::buildFileMenu() {
    auto add = [this](auto... a) { return addMenuAction(this, a...); };
    QMenu* file = menuBar()->addMenu(tr("&File"));
    add(
        file, tr("&Open experiment..."), QKeySequence::Open, [this] { chooseExperiment(); },
        "menuOpen");
    recentMenu_ = file->addMenu(tr("Open &recent"));
    recentMenu_->setObjectName("menuRecent");
    connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::fillRecentMenu);
    fillRecentMenu();
    save_ = add(
        file, tr("&Save"), QKeySequence::Save, [this] { saveExperimentInPlace(); }, "menuSave");
    add(
        file, tr("Save &as..."), standardOr(QKeySequence::SaveAs, tr("Ctrl+Shift+S")),
        [this] { chooseSaveAs(); }, "menuSaveAs");
    file->addSeparator();
    add(
        file, tr("Open r&ig file..."), QKeySequence(tr("Ctrl+Shift+O")),
        [this] {
            const QString path = QFileDialog::getOpenFileName(this, tr("Open rig file"), QString(),
                                                              tr("Rig files (*.json)"));
            if (!path.isEmpty()) devicesPanel_->openRigFile(path);
        },
        "menuOpenRig");
    exportAllMenu_ = add(
        file, tr("&Export all figures..."), QKeySequence(tr("Ctrl+E")),
        [this] { chooseExportFolder(); }, "menuExportAll");
    add(
        file, tr("Open results &folder"), QKeySequence(tr("Ctrl+Shift+F")),
        [this] { openResultsFolder(); }, "menuResultsFolder");
    file->addSeparator();
    add(
        file, tr("&Preferences..."), standardOr(QKeySequence::Preferences, tr("Ctrl+,")),
        [this] { showPreferences(); }, "menuPreferences");
    file->addSeparator();
    add(
        file, tr("&Quit"), standardOr(QKeySequence::Quit, tr("Ctrl+Q")), [this] { close(); },
        "menuQuit");
}

void MainWindow::buildRunMenu() {
    auto add = [this](auto... a) { return addMenuAction(this, a...); };
    QMenu* run = menuBar()->addMenu(tr("&Run"));
    addWithShortcut(run, runAll_, QKeySequence(Qt::Key_F5));
    addWithShortcut(run, runTraining_, QKeySequence(Qt::Key_F6));
    addWithShortcut(run, runFollowing_, QKeySequence(Qt::Key_F7));
    runSeeds_ = add(
        run, tr("Run over &seeds"), QKeySequence(Qt::Key_F8),
        [this] {
            tabs_->setCurrentWidget(seeds_);
            seeds_->requestRun();
        },
        "menuRunSeeds");
    runCompare_ = add(
        run, tr("&Compare with..."), QKeySequence(Qt::Key_F9),
        [this] {
            tabs_->setCurrentWidget(comparison_);
            comparison_->requestComparison();
        },
        "menuCompare");
    run->addSeparator();
    addWithShortcut(run, analyse_, QKeySequence(tr("Ctrl+Shift+A")));
    addWithShortcut(run, replay_, QKeySequence(tr("Ctrl+Shift+P")));
    calibrate_ = add(
        run, tr("Calibrate..."), QKeySequence(tr("Ctrl+Shift+K")),
        [this] {
            const QString path = QFileDialog::getOpenFileName(
                this, tr("Fit the scene to recorded training and test taps"), lastOutDir_,
                tr("Tap recordings (taps.csv *.csv)"));
            if (!path.isEmpty()) calibrateRecording(path);
        },
        "calibrate");
    calibrate_->setToolTip(
        tr("Fit the experiment's scene to recorded taps (from the real rig or a simulated one): "
           "noise, drift, dead taxels and gains with their uncertainties, the effects the taps "
           "call for, and how well the fitted scene reproduces them"));
    updateActions();
    run->addSeparator();
    addWithShortcut(run, cancel_, QKeySequence(Qt::Key_Escape));
}

void MainWindow::buildViewMenu() {
    auto add = [this](auto... a) { return addMenuAction(this, a...); };
    QMenu* view = menuBar()->addMenu(tr("&View"));
    // Ctrl+1 ... Ctrl+4 in the order docs/window.md lists the docks, Ctrl+5 the tool bar.
    int number = 1;
    for (const char* name : {"sceneDock", "devicesDock", "protocolDock", "logDock"}) {
        auto* dock = findChild<QDockWidget*>(name);
        QAction* toggle = dock->toggleViewAction();
        toggle->setShortcut(QKeySequence(tr("Ctrl+%1").arg(number++)));
        toggle->setObjectName(dock->objectName() + "Toggle");
        view->addAction(toggle);
    }
    QAction* toolbar = runBar_->toggleViewAction();
    toolbar->setShortcut(QKeySequence(tr("Ctrl+%1").arg(number)));
    toolbar->setObjectName("runToolBarToggle");
    view->addAction(toolbar);
    view->addSeparator();
    pauseLive_ = add(
        view, tr("&Pause the live view"), QKeySequence(tr("Ctrl+Space")),
        [this] { live_->setPaused(!live_->paused()); }, "menuPauseLive");
    pauseLive_->setCheckable(true);
    connect(live_, &LiveView::pausedChanged, pauseLive_, &QAction::setChecked);
    add(
        view, tr("&Reset the layout"), QKeySequence(tr("Ctrl+Shift+L")), [this] { resetLayout(); },
        "menuResetLayout");
}

void MainWindow::buildHelpMenu() {
    auto add = [this](auto... a) { return addMenuAction(this, a...); };
    QMenu* help = menuBar()->addMenu(tr("&Help"));
    add(
        help, tr("&Documentation"), QKeySequence::HelpContents, [this] { openDocumentation(); },
        "menuDocs");
    add(
        help, tr("&About ActiveTouch Workbench"), QKeySequence(tr("Ctrl+F1")),
        [this] { showAbout(); }, "menuAbout");
    add(
        help, tr("About &Qt"), QKeySequence(tr("Ctrl+Shift+F1")),
        [this] { QMessageBox::aboutQt(this); }, "menuAboutQt");
}

}  // namespace activetouch
