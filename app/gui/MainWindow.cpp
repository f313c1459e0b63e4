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
#include "app/figures/SeedFigures.h"
#include "app/figures/SweepFigures.h"
#include "app/figures/ValidationFigures.h"
#include "app/gui/ComparisonTab.h"
#include "app/gui/DevicesPanel.h"
#include "app/gui/FollowingTab.h"
#include "app/gui/LiveView.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/ProtocolPanel.h"
#include "app/gui/ScenePanel.h"
#include "app/gui/SeedsTab.h"
#include "app/gui/WholeFile.h"
#include "core/run/RunFolder.h"
#include "core/experiment/RunPlan.h"
#include "core/run/SeedRates.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "devices/simulated/SimulatedWorld.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {
/// `table` as one rule's confusion: a row per shape traced, a column per shape named; the cells
/// off the diagonal that are not zero stand out.
void fillConfusion(QTableWidget* table, const RecognitionConfusion& confusion, bool smoothed) {
    const auto& counts = smoothed ? confusion.smoothed : confusion.raw;
    const int n = static_cast<int>(confusion.labels.size());
    table->clear();
    table->setRowCount(n);
    table->setColumnCount(n);
    QStringList names;
    for (const auto& s : confusion.labels) names << QString::fromStdString(s);
    table->setHorizontalHeaderLabels(names);
    table->setVerticalHeaderLabels(names);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const int count = counts[std::size_t(a)][std::size_t(b)];
            auto* cell = new QTableWidgetItem(QString::number(count));
            if (a != b && count > 0) cell->setBackground(QColor(255, 220, 200));
            table->setItem(a, b, cell);
        }
}
}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent), runs_(feed_), devices_(feed_) {
    setWindowTitle(tr("ActiveTouch Workbench"));
    setObjectName("mainWindow");
    QSettings settings;
    outputBase_ = settings.value("outputBase", QDir::current().filePath("results")).toString();

    tabs_ = new QTabWidget;
    live_ = new LiveView(feed_);
    tabs_->addTab(live_, tr("Live"));
    auto* validation = new QTabWidget;
    taps_ = new PlotPanel("figure5_taps");
    errors_ = new PlotPanel("figure6_errors");
    validation->addTab(errors_, tr("Errors by orientation and position (Figure 6)"));
    validation->addTab(taps_, tr("Taps across each edge (Figure 5)"));
    tabs_->addTab(validation, tr("Training && validation"));
    following_ = new FollowingTab;
    tabs_->addTab(following_, tr("Contour following"));
    auto* recognition = new QSplitter(Qt::Vertical);
    recognition_ = new PlotPanel("figure9_recognition");
    recognition->addWidget(recognition_);
    auto* confusionBox = new QGroupBox(
        tr("Confusion over the recognised trials (rows: the shape traced; columns: the shape "
           "named)"));
    auto* confusionRow = new QHBoxLayout(confusionBox);
    for (auto [table, title, name] :
         {std::tuple{&confusionRaw_, &confusionRawTitle_, "confusionPaperRule"},
          std::tuple{&confusionSmoothed_, &confusionSmoothedTitle_, "confusionSmoothed"}}) {
        auto* column = new QVBoxLayout;
        *title = new QLabel;
        *table = new QTableWidget;
        (*table)->setObjectName(name);
        (*table)->setEditTriggers(QAbstractItemView::NoEditTriggers);
        column->addWidget(*title);
        column->addWidget(*table, 1);
        confusionRow->addLayout(column, 1);
    }
    recognition->addWidget(confusionBox);
    recognition->setStretchFactor(0, 4);
    tabs_->addTab(recognition, tr("Recognition"));
    auto* sweeps = new QTabWidget;
    sweepPerception_ = new PlotPanel("sweep_a_sequential_perception");
    sweepFollowing_ = new PlotPanel("sweep_b_following");
    sweepCompute_ = new PlotPanel("sweep_c_compute");
    sweeps->addTab(sweepPerception_, tr("(a) taps per decision"));
    sweeps->addTab(sweepFollowing_, tr("(b) following steps"));
    sweeps->addTab(sweepCompute_, tr("(c) compute"));
    sweeps->setToolTip(
        tr("Run an experiment with sweeps, such as experiments/accuracy_vs_time.json"));
    tabs_->addTab(sweeps, tr("Accuracy vs time"));
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
                if (!path.isEmpty()) startComparison(path, first, last);
            });
    connect(comparison_, &ComparisonTab::trialPairRequested, this,
            [this](quint64 seed, FollowingMode mode, const QString& label, int trial) {
                startTrialPair(seed, mode, label, trial);
            });
    setCentralWidget(tabs_);
    const QString training =
        tr("Click Run whole protocol, or Run training & validation, to tap the "
           "training and test sets on the rig and validate the classifier.");
    taps_->setEmptyHint(training);
    errors_->setEmptyHint(training);
    recognition_->setEmptyHint(recognitionHint());
    for (PlotPanel* p : {sweepPerception_, sweepFollowing_, sweepCompute_})
        p->setEmptyHint(
            tr("No sweeps measured yet. Open experiments/accuracy_vs_time.json (or any "
               "experiment with a \"sweeps\" section) and click Run whole protocol "
               "to measure what accuracy costs in time."));
    for (PlotPanel* p : plotPanels()) {
        connect(p, &PlotPanel::exported, this, &MainWindow::log);
        connect(p, &PlotPanel::failed, this, &MainWindow::showError);
    }

    scene_ = new ScenePanel;
    auto* sceneDock = new QDockWidget(tr("Scene"));
    sceneDock->setObjectName("sceneDock");
    sceneDock->setWidget(scene_);
    addDockWidget(Qt::LeftDockWidgetArea, sceneDock);
    connect(scene_, &ScenePanel::failed, this, &MainWindow::showError);
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

    auto* bar = addToolBar(tr("Run"));
    bar->setObjectName("runToolBar");
    bar->addAction(tr("Open..."), this, [this] {
        const QString path = QFileDialog::getOpenFileName(this, tr("Open an experiment"),
                                                          QFileInfo(experimentPath_).path(),
                                                          tr("Experiments (*.json)"));
        if (!path.isEmpty()) openExperiment(path);
    });
    bar->addAction(tr("Save as..."), this, [this] {
        const QString path = QFileDialog::getSaveFileName(
            this, tr("Save the experiment"), experimentPath_, tr("Experiments (*.json)"));
        if (!path.isEmpty()) saveExperiment(path);
    });
    bar->addSeparator();
    runAll_ = bar->addAction(tr("Run whole protocol"), this,
                             [this] { startRun(RunController::What::Everything); });
    runAll_->setObjectName("runAll");
    runTraining_ = bar->addAction(tr("Run training && validation"), this,
                                  [this] { startRun(RunController::What::TrainingOnly); });
    runFollowing_ = bar->addAction(tr("Run following"), this,
                                   [this] { startRun(RunController::What::FollowingOnly); });
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
    exportAll_ = bar->addAction(tr("Export all figures..."), this, [this] {
        const QString dir =
            QFileDialog::getExistingDirectory(this, tr("Export all figures into"), lastOutDir_);
        if (!dir.isEmpty()) exportAllFigures(dir);
    });

    progress_ = new QProgressBar;
    progress_->setRange(0, 1);
    progress_->setValue(0);
    progress_->setFormat(tr("idle"));
    progress_->setMinimumWidth(320);
    status_ = new QLabel;
    statusBar()->addPermanentWidget(status_, 1);
    statusBar()->addPermanentWidget(progress_);

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

    restoreGeometry(settings.value("geometry").toByteArray());
    restoreState(settings.value("windowState").toByteArray());
    const QString last = settings.value("lastExperiment").toString();
    const QString fallback = QDir(ACTIVETOUCH_SOURCE_DIR).filePath("experiments/paper.json");
    if (!(QFileInfo::exists(last) && openExperiment(last)) && QFileInfo::exists(fallback))
        openExperiment(fallback);
    updateActions();
}

MainWindow::~MainWindow() {
    stopRunNow();
}

QList<PlotPanel*> MainWindow::plotPanels() const {
    return {live_->barsPanel(),
            live_->tracesPanel(),
            taps_,
            errors_,
            following_->activePanel(),
            following_->passivePanel(),
            following_->replayPanel(),
            recognition_,
            sweepPerception_,
            sweepFollowing_,
            sweepCompute_,
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

namespace {
/// The experiment file at `path`, read with every check a run makes; its document in `j`.
ExperimentSpec readExperimentChecked(const QString& path, Json& j) {
    j = readExperimentFile(path.toStdString());
    ExperimentSpec spec =
        parseExperiment(j, path.toStdString(), QFileInfo(path).path().toStdString());
    validateEffects(spec.scene);
    return spec;
}
}  // namespace

bool MainWindow::openExperiment(const QString& path) {
    try {
        Json j;
        ExperimentSpec spec = readExperimentChecked(path, j);
        // Only a fully valid file replaces the session.
        spec_ = spec;
        experimentJson_ = j;
        experimentPath_ = path;
        scene_->showScene(spec_.scene);
        protocol_->showExperiment(spec_, experimentJson_);
        devicesPanel_->setScene(spec_.scene);
        setWindowTitle(tr("ActiveTouch Workbench - %1").arg(QFileInfo(path).fileName()));
        QSettings().setValue("lastExperiment", path);
        log(tr("opened %1 (%2)").arg(path, QString::fromStdString(spec_.name)));
        for (const std::string& c : untrainedEdgeCautions(spec_))
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

QString MainWindow::recognitionHint() const {
    return tr(
        "The active paths are recognised after active following: click Run whole protocol, "
        "or Run following once the classifier is trained.");
}

QString MainWindow::newRunDirectory(const QString& stem) const {
    return QDir(outputBase_)
        .filePath(stem + "-" + QDateTime::currentDateTime().toString("yyyyMMdd-hhmmss-zzz"));
}

bool MainWindow::startRun(RunController::What what) {
    const auto toRun = experimentToRun();
    if (!toRun) return false;
    // With devices connected, the run takes its taps on them; otherwise on the simulated rig.
    std::shared_ptr<const ConnectedRig> connected;
    if (devices_.session()->connected()) {
        QString why;
        connected = devices_.session()->lend(&why);
        if (!connected) {
            showError(tr("The run cannot use the connected devices: %1.").arg(why));
            return false;
        }
    }
    return launch(*toRun, what, QString::fromStdString(toRun->name), connected);
}

bool MainWindow::startSeedRun(std::uint64_t seed) {
    auto toRun = seedsSpec_ ? seedsSpec_ : experimentToRun();
    if (!toRun) return false;
    // A seed stands for a whole run on the simulated rig, as in the seeds run, whatever devices
    // are connected.
    toRun->scene.seed = seed;
    if (!launch(*toRun, RunController::What::Everything,
                QString("%1_seed%2").arg(QString::fromStdString(toRun->name)).arg(seed), nullptr))
        return false;
    tabs_->setCurrentWidget(following_);
    return true;
}

bool MainWindow::analyseRecording(const QString& path) {
    return startOnRecording(path, false);
}

bool MainWindow::replayRun(const QString& runDir) {
    return startOnRecording(runDir, true);
}

bool MainWindow::startOnRecording(const QString& path, bool replay) {
    const auto toRun = experimentToRun();
    if (!toRun) return false;
    std::shared_ptr<RecordedRun> recorded;
    try {
        if (replay) {
            recorded =
                std::make_shared<RecordedRun>(readRecordedRun(path.toStdString(), toRun->classes));
        } else {
            recorded = std::make_shared<RecordedRun>();
            recorded->name = path.toStdString();
            recorded->taps = readTapCsv(recorded->name, toRun->classes, &recorded->tapsCutOff);
        }
        checkRecordingCovers(*toRun, recorded->taps,
                             FingertipContactModel(toRun->scene.fingertip).taxelCount(),
                             recorded->name);
        if (replay) replayedTrialsFor(*toRun, recorded->trials, recorded->name);
        for (const std::string& c : {recorded->tapsCutOff, recorded->trialsCutOff})
            if (!c.empty())
                log(tr("the recording in %1 was cut short at the end, as by a run stopped while "
                       "writing: %2; that tap is left out")
                        .arg(path, QString::fromStdString(c)));
    } catch (const std::exception& e) {
        showError((replay ? tr("Could not replay %1:\n%2") : tr("Could not analyse %1:\n%2"))
                      .arg(path, e.what()));
        return false;
    }
    return launch(*toRun,
                  replay ? RunController::What::Everything : RunController::What::TrainingOnly,
                  QString::fromStdString(toRun->name) + (replay ? "_replay" : "_analysis"), nullptr,
                  recorded);
}

bool MainWindow::mayWriteRun(const ExperimentSpec& spec, double runs, const QString& dir) {
    // A plan past the bounds (docs/limits.md) runs only when the user says it is meant.
    const RunPlan plan = planOf(spec).times(runs);
    if (const PlanProblem problem =
            planProblem(plan, "the experiment", devices_.session()->connected());
        !problem.empty()) {
        QMessageBox ask(QMessageBox::Question, tr("ActiveTouch Workbench"),
                        tr("%1 asks for more than a run should:\n%2\n\nRun it anyway?")
                            .arg(QString::fromStdString(spec.name),
                                 QString::fromStdString(problem.problem)),
                        QMessageBox::Yes | QMessageBox::No, this);
        ask.setObjectName("longPlanQuestion");
        ask.setDefaultButton(QMessageBox::No);
        if (ask.exec() != QMessageBox::Yes) {
            log(tr("not started: %1").arg(QString::fromStdString(problem.problem)));
            return false;
        }
    }
    // A folder never holds two runs' files: one that holds a run is replaced only when asked.
    if (holdsRun(dir.toStdString())) {
        QMessageBox ask(QMessageBox::Question, tr("ActiveTouch Workbench"),
                        tr("%1 already holds a run. Replace it? Its files are removed first.")
                            .arg(dir),
                        QMessageBox::Yes | QMessageBox::No, this);
        ask.setObjectName("replaceRunQuestion");
        ask.setDefaultButton(QMessageBox::No);
        if (ask.exec() != QMessageBox::Yes) return false;
    }
    return true;
}

bool MainWindow::launch(const ExperimentSpec& spec, RunController::What what, const QString& stem,
                        std::shared_ptr<const ConnectedRig> connected,
                        std::shared_ptr<const RecordedRun> recorded) {
    const QString dir = newRunDirectory(stem);
    if (!mayWriteRun(spec, recorded ? 0 : 1, dir)) return false;  // a recording takes no taps
    if (!runs_.start(spec, dir, what, static_cast<Pace>(pace_->currentIndex()), last_, connected,
                     recorded))
        return false;
    countingSeeds_ = false;
    lastOutDir_ = dir;
    int recordedTaps = recorded ? static_cast<int>(recorded->taps.size()) : 0;
    if (recorded)
        for (const RecordedTrial& t : recorded->trials)
            recordedTaps += static_cast<int>(t.taps.size());
    progress_->setRange(0, recorded ? recordedTaps : plannedTapEstimate(spec));
    progress_->setValue(0);
    if (recorded && recorded->replay())
        log(tr("replay started: %1 on the run recorded in %2 (%3 taps, %4 trials), writing %5")
                .arg(QString::fromStdString(spec.name), QString::fromStdString(recorded->name))
                .arg(recordedTaps)
                .arg(recorded->trials.size())
                .arg(dir));
    else if (recorded)
        log(tr("analysis started: %1 on the %2 taps recorded in %3, writing %4")
                .arg(QString::fromStdString(spec.name))
                .arg(recorded->taps.size())
                .arg(QString::fromStdString(recorded->name), dir));
    else
        log(tr("run started: %1, seed %2, on %3, writing %4")
                .arg(QString::fromStdString(spec.name), QString::number(spec.scene.seed),
                     connected ? tr("the connected rig (%1)")
                                     .arg(QString::fromStdString(connected->description))
                               : tr("the simulated rig"),
                     dir));
    updateActions();
    return true;
}

bool MainWindow::startSeeds(std::uint64_t first, std::uint64_t last) {
    const auto toRun = experimentToRun();
    if (!toRun) return false;
    const ExperimentSpec& spec = *toRun;
    const QString name = QString::fromStdString(spec.name);
    const QString dir = newRunDirectory(name + "_seeds");
    if (!mayWriteRun(spec, double(last - first + 1), dir)) return false;
    if (!runs_.startSeeds(spec, first, last, dir)) return false;
    countingSeeds_ = true;
    lastSeedsDir_ = dir;
    seedsSpec_ = spec;
    seeds_->begin(name);
    tabs_->setCurrentWidget(seeds_);
    progress_->setRange(0, static_cast<int>(std::min<std::uint64_t>(last - first + 1, INT_MAX)));
    progress_->setValue(0);
    log(tr("seeds run started: %1, seeds %2-%3, each a whole run on the simulated rig, %4 at a "
           "time, writing %5")
            .arg(name)
            .arg(first)
            .arg(last)
            .arg(defaultSeedJobs())
            .arg(dir));
    updateActions();
    return true;
}

bool MainWindow::startComparison(const QString& otherPath, std::uint64_t first,
                                 std::uint64_t last) {
    const auto toRun = experimentToRun();
    if (!toRun) return false;
    ExperimentSpec other;
    try {
        Json j;
        other = readExperimentChecked(otherPath, j);
        checkComparable(*toRun, other);
    } catch (const std::exception& e) {
        showError(tr("Could not compare with %1:\n%2").arg(otherPath, e.what()));
        return false;
    }
    const QString a = QString::fromStdString(toRun->name), b = QString::fromStdString(other.name);
    const QString dir = newRunDirectory(a + "_vs_" + b);
    if (!mayWriteRun(*toRun, double(last - first + 1), dir) ||
        !mayWriteRun(other, double(last - first + 1), dir))
        return false;
    if (!runs_.startComparison(*toRun, other, first, last, dir)) return false;
    countingSeeds_ = true;
    lastComparisonDir_ = dir;
    compared_ = std::make_pair(*toRun, other);
    comparison_->begin(a, b, first, last);
    tabs_->setCurrentWidget(comparison_);
    progress_->setRange(0, static_cast<int>(std::min<std::uint64_t>(last - first + 1, INT_MAX)));
    progress_->setValue(0);
    log(tr("comparison started: %1 (A) against %2 (B, %3), seeds %4-%5, trial by trial, %6 at a "
           "time, writing %7")
            .arg(a, b, otherPath)
            .arg(first)
            .arg(last)
            .arg(defaultSeedJobs())
            .arg(dir));
    updateActions();
    return true;
}

bool MainWindow::startTrialPair(std::uint64_t seed, FollowingMode mode, const QString& label,
                                int trial) {
    if (!compared_ || runs_.running()) return false;
    if (!runs_.startTrialPair(compared_->first, compared_->second, seed, mode, label.toStdString(),
                              trial, lastComparisonDir_))
        return false;
    countingSeeds_ = true;
    progress_->setRange(0, 1);
    progress_->setValue(0);
    log(tr("running seed %1 in %2 (A) and %3 (B) to show %4 trial %5 of %6")
            .arg(seed)
            .arg(QString::fromStdString(compared_->first.name),
                 QString::fromStdString(compared_->second.name), modeName(mode))
            .arg(trial)
            .arg(label));
    updateActions();
    return true;
}

void MainWindow::showComparison(std::shared_ptr<const PairedComparison> comparison,
                                const QString& dir, bool cancelled) {
    comparison_->finish(*comparison, dir, cancelled);
    QString figures;
    try {
        const QStringList files = writeComparisonFigures(*comparison, dir);
        if (!files.isEmpty()) figures = tr("; figure %1").arg(files.first());
    } catch (const std::exception& e) {
        showError(tr("Could not write the comparison figure: %1").arg(e.what()));
    }
    const QString state = cancelled ? tr("cancelled") : tr("finished");
    progress_->setFormat(tr("comparison %1: %2 seeds").arg(state).arg(comparison->seeds));
    status_->setText(tr("comparison %1, results in %2").arg(state, dir));
    const PairedRate& active = comparison->activeCompleted;
    log(tr("comparison %1 after %2 seeds: active completed %3 (A) and %4 (B) of %5, %6 only by "
           "A, %7 only by B (McNemar p %8); compare.csv and compare.json in %9%10")
            .arg(state)
            .arg(comparison->seeds)
            .arg(active.a().count)
            .arg(active.b().count)
            .arg(active.pairs())
            .arg(active.onlyA)
            .arg(active.onlyB)
            .arg(active.mcnemarP(), 0, 'g', 3)
            .arg(dir, figures));
    emit runEnded(!cancelled);
}

void MainWindow::showTrialPair(const std::shared_ptr<const TrialPairRun>& pair,
                               const QString& dir) {
    comparison_->showTrialPair(*pair);
    const QString how =
        tr("seed %1, %2 trial %3 of %4: A %5, B %6")
            .arg(pair->seed)
            .arg(modeName(pair->a.result.mode))
            .arg(pair->a.trial)
            .arg(QString::fromStdString(pair->a.label), QString::fromStdString(endedText(pair->a)),
                 QString::fromStdString(endedText(pair->b)));
    progress_->setFormat(tr("trial shown in both experiments"));
    status_->setText(how);
    // The same table and figure compare --show writes, beside the comparison's own files.
    QString files;
    try {
        writeTrialPairTable(*pair, dir.toStdString());
        writeTrialPairFigures(*pair, dir);
        files = tr("; its table and figure %1.* in %2")
                    .arg(QString::fromStdString(trialPairFileStem(*pair)), dir);
    } catch (const std::exception& e) {
        showError(tr("Could not write the trial's table and figure: %1").arg(e.what()));
    }
    log(how + files);
    emit runEnded(true);
}

void MainWindow::showSeeds(std::shared_ptr<const SeedRates> rates, const QString& dir,
                           bool cancelled) {
    seeds_->finish(dir, cancelled);
    QString figures;
    try {
        const QStringList files = writeSeedFigures(*rates, seeds_->experiment(), dir);
        if (!files.isEmpty()) figures = tr("; figure %1").arg(files.first());
    } catch (const std::exception& e) {
        showError(tr("Could not write the seeds figure: %1").arg(e.what()));
    }
    const QString state = cancelled ? tr("cancelled") : tr("finished");
    progress_->setFormat(tr("seeds %1: %2").arg(state).arg(rates->seeds.size()));
    status_->setText(tr("seeds %1, results in %2").arg(state, dir));
    const Rate completed = rates->activeCompleted(), lost = rates->passiveLost();
    log(tr("seeds run %1 after %2 seeds: active completed %3/%4, passive lost %5/%6; rates.csv "
           "and rates.json in %7%8")
            .arg(state)
            .arg(rates->seeds.size())
            .arg(completed.count)
            .arg(completed.total)
            .arg(lost.count)
            .arg(lost.total)
            .arg(dir, figures));
    emit runEnded(!cancelled);
}

void MainWindow::cancelRun() {
    if (!runs_.running()) return;
    runs_.cancel();
    log(tr("cancelling: the run stops after the tap in flight; every tap taken is kept"));
}

void MainWindow::showRun(std::shared_ptr<const RunResult> result, const QString& dir) {
    const RunResult& r = *result;
    const bool trainingRun =
        !r.taps.empty();  // a following-only run keeps the training figures shown
    // Of recorded taps, none taken: an analysis, or a replay that also followed on them.
    const bool replay = r.rig.rfind("replay of ", 0) == 0;
    const bool analysis = replay || r.rig.rfind("recording ", 0) == 0;
    last_ = result;
    lastOutDir_ = dir;
    if (trainingRun) buildTapFigure(taps_->plot(), r);
    if (!r.validation.byClass.empty()) buildErrorFigure(errors_->plot(), r);
    for (auto* p : {taps_, errors_}) p->plot().replot();
    following_->showRun(result);
    recognition_->setEmptyHint(r.spec.recognition.enabled
                                   ? recognitionHint()
                                   : tr("This experiment has no recognition step: add a "
                                        "\"recognition\" section, as experiments/paper.json has, "
                                        "to recognise the shapes from the traced paths."));
    buildRecognitionFigure(recognition_->plot(), r);
    recognition_->plot().replot();
    if (!r.sweeps.empty()) {
        if (analysis)
            for (PlotPanel* p : {sweepPerception_, sweepFollowing_})
                p->setEmptyHint(
                    tr("This sweep takes new taps and follows contours on simulated "
                       "rigs: run the experiment to measure it. An analysed or replayed "
                       "recording measures only the compute sweep (c), on its own taps."));
        buildPerceptionSweepFigure(sweepPerception_->plot(), r);
        buildFollowingSweepFigure(sweepFollowing_->plot(), r);
        buildComputeSweepFigure(sweepCompute_->plot(), r);
        for (auto* p : {sweepPerception_, sweepFollowing_, sweepCompute_}) p->plot().replot();
    }
    // Confusion over the recognised trials, traced shape x named, for each rule.
    const RecognitionConfusion confusion = recognitionConfusion(r);
    fillConfusion(confusionRaw_, confusion, false);
    fillConfusion(confusionSmoothed_, confusion, true);
    confusionRawTitle_->setText(
        tr("paper's rule: %1 % named rightly").arg(100.0 * r.recognitionAccuracy, 0, 'f', 0));
    confusionSmoothedTitle_->setText(tr("smoothed histograms (sigma %1 bins): %2 % named rightly")
                                         .arg(r.spec.recognition.smoothingSigmaBins)
                                         .arg(100.0 * r.recognitionAccuracySmoothed, 0, 'f', 0));
    progress_->setRange(0, std::max(1, progress_->value()));
    progress_->setValue(progress_->maximum());
    const QString state =
        r.cancelled ? tr("cancelled") : (r.failure.empty() ? tr("finished") : tr("failed"));
    // Taps taken: simulated ones (sweeps included), or those of the devices or the recording.
    std::uint64_t taps = r.tapsSimulated;
    if (r.rig != "simulated") {
        taps = r.taps.size();
        for (const auto& t : r.trials) taps += t.result.taps.size();
    }
    const QString what = replay ? tr("replay") : analysis ? tr("analysis") : tr("run");
    progress_->setFormat(tr("%1: %2 taps").arg(state).arg(taps));
    status_->setText(tr("%1, results in %2").arg(state, dir));
    if (!r.validation.byClass.empty())
        log(tr("validation: angle error %1 deg, position error %2 mm, %3")
                .arg(r.validation.angleError_deg, 0, 'f', 2)
                .arg(r.validation.positionError_mm, 0, 'f', 3)
                .arg(QString::fromStdString(r.validation.validRange.text())));
    if (const std::string note = followingClassifierNote(r); !note.empty())
        log(QString::fromStdString(note));
    for (const auto& t : r.trials)
        log(tr("%1 %2 trial %3: %4")
                .arg(modeName(t.result.mode), QString::fromStdString(t.label))
                .arg(t.trial)
                .arg(QString::fromStdString(t.result.detail)));
    log(tr("%1 %2: %3 taps, results in %4").arg(what, state).arg(taps).arg(dir));
    if (!r.failure.empty())
        showError(tr("The run stopped: %1. Every tap taken so far is in %2/data.")
                      .arg(QString::fromStdString(r.failure), dir));
    emit runEnded(!r.cancelled && r.failure.empty());
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
    runFollowing_->setEnabled(!busy && ready && last_ && last_->classifier.trained());
    cancel_->setEnabled(busy);
    seeds_->setRunnable(!busy && ready);
    comparison_->setRunnable(!busy && ready);
    exportAll_->setEnabled(!busy && last_ != nullptr);
}

void MainWindow::stopRunNow() {
    // A run in flight stops at once: the devices drop the tap or move in progress (a run on the
    // connected rig ends its trial there, keeping every finished tap); never wait long on it.
    runs_.cancel();
    devices_.session()->interrupt();
    runs_.stopAndWait(2000);
}

void MainWindow::closeEvent(QCloseEvent* event) {
    stopRunNow();
    QSettings settings;
    settings.setValue("geometry", saveGeometry());
    settings.setValue("windowState", saveState());
    settings.setValue("pace", pace_->currentIndex());
    settings.setValue("outputBase", outputBase_);
    event->accept();
}

}  // namespace activetouch
