#include "app/gui/MainWindow.h"

#include <QAction>
#include <QCloseEvent>
#include <QComboBox>
#include <QDateTime>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QIcon>
#include <QLabel>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>
#include <QTabWidget>
#include <QTableWidget>
#include <QToolBar>
#include <QVBoxLayout>
#include <algorithm>
#include <climits>
#include <tuple>

#include "app/figures/ComparisonFigures.h"
#include "app/figures/FollowingFigures.h"
#include "app/figures/Installation.h"
#include "app/figures/SeedFigures.h"
#include "app/figures/SweepFigures.h"
#include "app/figures/ValidationFigures.h"
#include "app/gui/ComparisonTab.h"
#include "app/gui/DevicesPanel.h"
#include "app/gui/FollowingTab.h"
#include "app/gui/LiveView.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/ProtocolPanel.h"
#include "app/gui/ResultTabs.h"
#include "app/gui/ScenePanel.h"
#include "app/gui/SeedsTab.h"
#include "app/gui/WholeFile.h"
#include "core/analysis/SeedRates.h"
#include "core/experiment/ReachCautions.h"
#include "core/experiment/RunPlan.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "core/run/ExperimentFiles.h"
#include "core/run/RunFolder.h"
#include "core/run/Sweeps.h"
#include "devices/simulated/SimulatedWorld.h"
#include "qcustomplot.h"

namespace activetouch {

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent), runs_(feed_), devices_(feed_) {
    setWindowTitle(tr("ActiveTouch Workbench[*]"));
    setObjectName("mainWindow");
    setAcceptDrops(true);
    setWindowIcon(QIcon(QDir(iconDirectory()).filePath("activetouch.svg")));
    QSettings settings;
    resultsFolder_ = settings.value("resultsFolder", defaultResultsFolder()).toString();
    outputBase_ = resultsFolder_;
    buildTabs();
    buildDocks();
    buildToolBar(settings);
    buildStatusBar();
    buildMenus();
    connectRuns();
    // The layout as built is the one Reset the layout goes back to; a saved one replaces it.
    defaultState_ = saveState();
    if (!restoreGeometry(settings.value("geometry").toByteArray())) fitToScreen();
    restoreState(settings.value("windowState").toByteArray());
    const QString last = settings.value("lastExperiment").toString();
    const QString fallback = QDir(experimentsDirectory()).filePath("paper.json");
    if (!(QFileInfo::exists(last) && openExperiment(last)) && QFileInfo::exists(fallback))
        openExperiment(fallback);
    connect(scene_, &ScenePanel::changed, this, &MainWindow::updateModified);
    connect(protocol_, &ProtocolPanel::changed, this, &MainWindow::updateModified);
    updateActions();
}

void MainWindow::buildTabs() {
    tabs_ = new QTabWidget;
    live_ = new LiveView(feed_);
    tabs_->addTab(live_, tr("Live"));
    validation_ = new ValidationTab;
    tabs_->addTab(validation_, tr("Training && validation"));
    following_ = new FollowingTab;
    tabs_->addTab(following_, tr("Contour following"));
    recognition_ = new RecognitionTab;
    tabs_->addTab(recognition_, tr("Recognition"));
    sweeps_ = new SweepsTab;
    tabs_->addTab(sweeps_, tr("Accuracy vs time"));
    connect(sweeps_, &SweepsTab::settingRequested, this, [this](const SweepSetting& s) {
        // The point's setting into the protocol panel, then following with it.
        protocol_->setField("following", "follow_step_mm", s.followStep_mm);
        protocol_->setField("following", "reposition_step_mm", s.repositionStep_mm);
        protocol_->setField("following", "belief_threshold", s.beliefThreshold);
        if (startRun(RunController::What::FollowingOnly)) tabs_->setCurrentWidget(following_);
    });
    connect(sweeps_, &SweepsTab::standardSweepsRequested, this, [this] {
        auto toRun = experimentToRun();
        if (!toRun) return;
        toRun->sweeps = standardSweeps();
        launch(*toRun, RunController::What::Everything,
               QString::fromStdString(toRun->name) + "_sweeps", nullptr);
    });
    seeds_ = new SeedsTab;
    tabs_->addTab(seeds_, tr("Rates over seeds"));
    connect(seeds_, &SeedsTab::runRequested, this,
            [this](std::uint64_t first, std::uint64_t last) { startSeeds(first, last); });
    connect(seeds_, &SeedsTab::seedRunRequested, this, &MainWindow::startSeedRun);
    comparison_ = new ComparisonTab;
    tabs_->addTab(comparison_, tr("Compare"));
    connect(comparison_, &ComparisonTab::compareRequested, this,
            [this](std::uint64_t first, std::uint64_t last) {
                const QString path = QFileDialog::getOpenFileName(
                    this, tr("Compare with the experiment (B)"), QFileInfo(experimentPath_).path(),
                    tr("Experiments (*.json)"));
                if (!path.isEmpty()) confirmComparison(path, first, last);
            });
    connect(comparison_, &ComparisonTab::trialPairRequested, this,
            [this](quint64 seed, FollowingMode mode, const QString& label, int trial) {
                startTrialPair(seed, mode, label, trial);
            });
    setCentralWidget(tabs_);
    for (PlotPanel* p : plotPanels()) {
        connect(p, &PlotPanel::exported, this, &MainWindow::log);
        connect(p, &PlotPanel::failed, this, &MainWindow::showError);
    }
}

void MainWindow::buildDocks() {
    scene_ = new ScenePanel;
    auto* sceneDock = new QDockWidget(tr("Scene"));
    sceneDock->setObjectName("sceneDock");
    sceneDock->setWidget(scene_);
    addDockWidget(Qt::LeftDockWidgetArea, sceneDock);
    connect(scene_, &ScenePanel::failed, this, &MainWindow::showError);
    connect(scene_, &ScenePanel::noted, this, &MainWindow::log);
    devicesPanel_ = new DevicesPanel(devices_.session());
    auto* devicesDock = new QDockWidget(tr("Devices"));
    devicesDock->setObjectName("devicesDock");
    devicesDock->setWidget(devicesPanel_);
    addDockWidget(Qt::LeftDockWidgetArea, devicesDock);
    protocol_ = new ProtocolPanel;
    auto* protocolDock = new QDockWidget(tr("Protocol"));
    protocolDock->setObjectName("protocolDock");
    protocolDock->setWidget(protocol_);
    addDockWidget(Qt::LeftDockWidgetArea, protocolDock);
    tabifyDockWidget(sceneDock, protocolDock);
    tabifyDockWidget(protocolDock, devicesDock);
    sceneDock->raise();
    // The panels scroll: they start at a width that leaves the plots the room, and a person may
    // widen them.
    resizeDocks({sceneDock}, {420}, Qt::Horizontal);
    connect(protocol_, &ProtocolPanel::resetRequested, this, [this] {
        protocol_->showExperiment(spec_, experimentJson_);
        log(tr("protocol panel: the settings of %1 shown again").arg(experimentPath_));
    });
    connect(devicesPanel_, &DevicesPanel::log, this, &MainWindow::log);
    connect(devicesPanel_, &DevicesPanel::failed, this, &MainWindow::showError);
    log_ = new QPlainTextEdit;
    log_->setReadOnly(true);
    log_->setObjectName("log");
    auto* logDock = new QDockWidget(tr("Log"));
    logDock->setObjectName("logDock");
    logDock->setWidget(log_);
    addDockWidget(Qt::BottomDockWidgetArea, logDock);
    resizeDocks({logDock}, {110}, Qt::Vertical);  // a few lines; the plots take the height
}

void MainWindow::buildToolBar(const QSettings& settings) {
    auto* bar = addToolBar(tr("Run"));
    runBar_ = bar;
    bar->setObjectName("runToolBar");
    bar->addAction(tr("Open..."), this, [this] { chooseExperiment(); });
    bar->addAction(tr("Save as..."), this, [this] { chooseSaveAs(); });
    bar->addSeparator();
    runAll_ = bar->addAction(tr("Run whole protocol"), this,
                             [this] { startRun(RunController::What::Everything); });
    runAll_->setObjectName("runAll");
    runTraining_ = bar->addAction(tr("Run training && validation"), this,
                                  [this] { startRun(RunController::What::TrainingOnly); });
    runTraining_->setObjectName("runTraining");
    runFollowing_ = bar->addAction(tr("Run following"), this,
                                   [this] { startRun(RunController::What::FollowingOnly); });
    runFollowing_->setObjectName("runFollowing");
    analyse_ = bar->addAction(tr("Analyse recording..."), this, [this] {
        const QString path =
            QFileDialog::getOpenFileName(this, tr("Analyse recorded training and test taps"),
                                         lastOutDir_, tr("Tap recordings (taps.csv *.csv)"));
        if (!path.isEmpty()) analyseRecording(path);
    });
    analyse_->setObjectName("analyseRecording");
    analyse_->setToolTip(
        tr("Train and validate the experiment as shown on recorded taps (a run's data/taps.csv, "
           "from the simulated or the real rig), taking no tap"));
    replay_ = bar->addAction(tr("Replay run..."), this, [this] {
        const QString dir = QFileDialog::getExistingDirectory(
            this, tr("Replay the run recorded in (a run's folder)"), lastOutDir_);
        if (!dir.isEmpty()) replayRun(dir);
    });
    replay_->setObjectName("replayRun");
    replay_->setToolTip(
        tr("Replay a run's recording (simulated or real rig) as a rig with the experiment as "
           "shown: train and validate on its taps, then run each trial on its recorded taps and "
           "see where other settings would have decided otherwise"));
    cancel_ = bar->addAction(tr("Cancel"), this, &MainWindow::cancelRun);
    cancel_->setObjectName("cancel");
    pace_ = new QComboBox;
    pace_->addItems({tr("as fast as possible"), tr("live frames (1 s per tap)"),
                     tr("robot time (2.5 s per tap)")});
    pace_->setCurrentIndex(settings.value("pace", 0).toInt());
    bar->addWidget(pace_);
    bar->addSeparator();
    exportAll_ =
        bar->addAction(tr("Export all figures..."), this, [this] { chooseExportFolder(); });
    for (QAction* a : {runAll_, runTraining_, runFollowing_, analyse_, replay_, cancel_})
        a->setToolTip(a->toolTip().isEmpty() ? a->text().remove('&') : a->toolTip());
}

void MainWindow::buildStatusBar() {
    progress_ = new QProgressBar;
    progress_->setRange(0, 1);
    progress_->setValue(0);
    progress_->setFormat(tr("idle"));
    progress_->setMinimumWidth(320);
    progress_->setMinimumWidth(200);
    status_ = new QLabel;
    status_->setMinimumWidth(80);
    resultsLabel_ = new QLabel;
    resultsLabel_->setObjectName("resultsFolderLabel");
    resultsLabel_->setTextFormat(Qt::RichText);
    resultsLabel_->setMinimumWidth(80);
    resultsLabel_->setMaximumWidth(420);
    connect(resultsLabel_, &QLabel::linkActivated, this, [this] { openResultsFolder(); });
    showResultsFolder();
    statusBar()->addPermanentWidget(status_, 1);
    statusBar()->addPermanentWidget(resultsLabel_);
    statusBar()->addPermanentWidget(progress_);
}

void MainWindow::connectRuns() {
    connect(&runs_, &RunController::progress, this,
            [this](int done, int planned, const QString& step, double left) {
                progress_->setRange(0, std::max(planned, done));
                progress_->setValue(done);
                progress_->setFormat((countingSeeds_ ? tr("%1 of %2 seeds, about %3 s left")
                                                     : tr("%1 of about %2 taps, about %3 s left"))
                                         .arg(done)
                                         .arg(planned)
                                         .arg(left, 0, 'f', 0));
                status_->setText(step);
            });
    connect(&runs_, &RunController::finished, this, &MainWindow::showRun);
    connect(&runs_, &RunController::seedFinished, seeds_, &SeedsTab::addSeed);
    connect(&runs_, &RunController::seedsFinished, this, &MainWindow::showSeeds);
    connect(&runs_, &RunController::comparisonSeedFinished, comparison_,
            [this](quint64 seed, const std::vector<PairedTrial>& pairs,
                   const std::shared_ptr<const PairedComparison>& soFar) {
                comparison_->addSeed(seed, pairs, *soFar);
            });
    connect(&runs_, &RunController::comparisonFinished, this, &MainWindow::showComparison);
    connect(&runs_, &RunController::trialPairFinished, this, &MainWindow::showTrialPair);
    connect(&runs_, &RunController::failed, this, [this](const QString& m) {
        seeds_->interrupted();
        comparison_->interrupted();
        showError(m);
        emit runEnded(false);
    });
    connect(&runs_, &RunController::idle, this, &MainWindow::updateActions);
}

MainWindow::~MainWindow() {
    stopRunNow();
}

QList<PlotPanel*> MainWindow::plotPanels() const {
    return {live_->barsPanel(),
            live_->tracesPanel(),
            validation_->tapsPanel(),
            validation_->errorsPanel(),
            following_->activePanel(),
            following_->passivePanel(),
            following_->replayPanel(),
            recognition_->panel(),
            sweeps_->perceptionPanel(),
            sweeps_->followingPanel(),
            sweeps_->computePanel(),
            sweeps_->perceptionOverSeedsPanel(),
            sweeps_->paretoOverSeedsPanel(),
            seeds_->ratesPanel(),
            comparison_->plotPanel(),
            comparison_->pairPanel()};
}

void MainWindow::setPace(Pace pace) {
    pace_->setCurrentIndex(static_cast<int>(pace));
}

void MainWindow::log(const QString& text) {
    log_->appendPlainText(QDateTime::currentDateTime().toString("hh:mm:ss  ") + text);
}

void MainWindow::showError(const QString& message) {
    log(tr("error: %1").arg(message));
    auto* box = new QMessageBox(QMessageBox::Warning, tr("ActiveTouch Workbench"), message,
                                QMessageBox::Ok, this);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->setObjectName("errorDialog");
    box->open();  // not modal to the event loop: runs and the live view go on
    emit errorShown(message);
}

bool MainWindow::openExperiment(const QString& path) {
    try {
        if (!QFileInfo::exists(path))
            throw InputError(path.toStdString(), "",
                             "no such file; it may have been moved or deleted (File > Open "
                             "experiment chooses another)");
        Json j;
        ExperimentSpec spec = loadCheckedExperiment(path.toStdString(), true, simulatedRigs(), &j);
        // Only a fully valid file replaces the session.
        spec_ = spec;
        experimentJson_ = j;
        experimentPath_ = path;
        scene_->showScene(spec_.scene);
        protocol_->showExperiment(spec_, experimentJson_);
        devicesPanel_->setScene(spec_.scene);
        live_->setFingertip(spec_.scene.fingertip, spec_.scene.tap.contactThreshold);
        setWindowTitle(tr("ActiveTouch Workbench - %1[*]").arg(QFileInfo(path).fileName()));
        QSettings().setValue("lastExperiment", path);
        rememberRecent(path);
        savedDocument_ = documentAsShown();
        setWindowModified(false);
        log(tr("opened %1 (%2)").arg(path, QString::fromStdString(spec_.name)));
        for (const auto& c : untrainedEdgeCautions(spec_))
            log(tr("caution: %1").arg(QString::fromStdString(c)));
        for (const auto& c : unresolvedFeatureCautions(spec_))
            log(tr("caution: %1").arg(QString::fromStdString(c)));
        updateActions();
        return true;
    } catch (const InputError& e) {
        showError(tr("Could not open %1:\n%2").arg(path, QString::fromStdString(e.what())));
    } catch (const std::exception& e) {
        showError(tr("Could not open %1: %2").arg(path, e.what()));
    }
    return false;
}

ExperimentSpec MainWindow::experimentAsShown() const {
    return experimentAsShown(nullptr);
}

ExperimentSpec MainWindow::experimentAsShown(Json* document) const {
    ExperimentSpec onPanelScene = spec_;
    onPanelScene.scene = scene_->sceneFromPanel(spec_.scene);
    const SceneSpec& scene = onPanelScene.scene;
    validateEffects(scene);
    if (const std::string problem = trainingObjectProblem(onPanelScene); !problem.empty())
        throw InputError("scene panel", "object", "training on it: " + problem);
    Json j = protocol_->patch(experimentJson_);
    j["scene"] = sceneToJson(scene);
    try {
        ExperimentSpec spec =
            parseExperiment(j, spec_.source, QFileInfo(experimentPath_).path().toStdString());
        spec.scene.source = spec_.scene.source;
        if (document) *document = std::move(j);
        return spec;
    } catch (const InputError& e) {
        // The protocol's classes may ask for edges the scene's object does not have.
        if (e.place().rfind("/scene", 0) == 0)
            throw InputError("scene panel", "object", e.problem());
        const QString field = protocol_->fieldAt(e.place());
        throw InputError("protocol panel",
                         field.isEmpty() ? e.place() : field.toStdString() + " (" + e.place() + ")",
                         e.problem());
    }
}

bool MainWindow::saveExperiment(const QString& path) {
    try {
        Json j;
        experimentAsShown(&j);  // only what can run is written
        const QString failed = writeFileWhole(path, QByteArray::fromStdString(j.dump(2) + "\n"));
        if (!failed.isEmpty())
            throw InputError(path.toStdString(), "",
                             "cannot write the file (" + failed.toStdString() +
                                 "); free space on its disk or choose a writable place; the "
                                 "file is as it was");
        log(tr("saved %1").arg(path));
        if (QFileInfo(path) == QFileInfo(experimentPath_)) {
            savedDocument_ = documentAsShown();
            setWindowModified(false);
        }
        return true;
    } catch (const std::exception& e) {
        showError(tr("Could not save: %1").arg(e.what()));
        return false;
    }
}

std::optional<ExperimentSpec> MainWindow::experimentToRun() {
    if (experimentPath_.isEmpty()) {
        showError(tr("Open an experiment first."));
        return std::nullopt;
    }
    try {
        return experimentAsShown();
    } catch (const std::exception& e) {
        showError(tr("The experiment as shown cannot run: %1").arg(e.what()));
        return std::nullopt;
    }
}

QStringList MainWindow::exportAllFigures(const QString& dir) {
    if (!last_) {
        showError(tr("There is no run to export yet."));
        return {};
    }
    try {
        const QStringList files = writeRunFigures(*last_, dir);
        log(tr("%1 figure files written to %2/figures").arg(files.size()).arg(dir));
        return files;
    } catch (const std::exception& e) {
        showError(tr("Could not export the figures: %1").arg(e.what()));
        return {};
    }
}

void MainWindow::updateActions() {
    const bool busy = runs_.running();
    const bool ready = !experimentPath_.isEmpty();
    runAll_->setEnabled(!busy && ready);
    runTraining_->setEnabled(!busy && ready);
    analyse_->setEnabled(!busy && ready);
    replay_->setEnabled(!busy && ready);
    if (calibrate_) calibrate_->setEnabled(ready);
    runFollowing_->setEnabled(!busy && ready && last_ && last_->classifier.trained());
    cancel_->setEnabled(busy);
    seeds_->setRunnable(!busy && ready);
    comparison_->setRunnable(!busy && ready);
    exportAll_->setEnabled(!busy && last_ != nullptr);
    exportAllMenu_->setEnabled(!busy && last_ != nullptr);
    save_->setEnabled(ready);
    runSeeds_->setEnabled(!busy && ready);
    runCompare_->setEnabled(!busy && ready);
}

void MainWindow::stopRunNow() {
    // A run in flight stops at once: the devices drop the tap or move in progress (a run on the
    // connected rig ends its trial there, keeping every finished tap); never wait long on it.
    runs_.cancel();
    devices_.session()->interrupt();
    runs_.stopAndWait(2000);
}

void MainWindow::closeEvent(QCloseEvent* event) {
    if (!maySwitchExperiment()) {
        event->ignore();
        return;
    }
    stopRunNow();
    QSettings settings;
    settings.setValue("geometry", saveGeometry());
    settings.setValue("windowState", saveState());
    settings.setValue("pace", pace_->currentIndex());
    event->accept();
}

}  // namespace activetouch
