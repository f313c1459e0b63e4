// MainWindow, its runs: starting each kind of run from what the window shows, asking before a
// long plan or a folder that holds a run, and showing what comes back.
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
#include <QLocale>
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
#include "app/gui/CalibrationDialog.h"
#include "app/gui/ComparisonTab.h"
#include "app/gui/DevicesPanel.h"
#include "app/gui/FollowingTab.h"
#include "app/gui/LiveView.h"
#include "app/gui/MainWindow.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/ProtocolPanel.h"
#include "app/gui/ResultTabs.h"
#include "app/gui/ScenePanel.h"
#include "app/gui/SeedsTab.h"
#include "app/gui/WholeFile.h"
#include "core/analysis/SeedRates.h"
#include "core/analysis/SweepRates.h"
#include "core/experiment/RunPlan.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "core/run/ExperimentFiles.h"
#include "core/run/RunFolder.h"
#include "devices/simulated/SimulatedWorld.h"
#include "qcustomplot.h"

namespace activetouch {

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

CalibrationDialog* MainWindow::calibrateRecording(const QString& path) {
    const auto toRun = experimentToRun();
    if (!toRun) return nullptr;
    auto* dialog = new CalibrationDialog(*toRun, path, this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    connect(dialog, &CalibrationDialog::fitFinished, this, [this, path](bool ok) {
        log(ok ? tr("calibrated the scene to %1").arg(path)
               : tr("could not calibrate the scene to %1").arg(path));
    });
    dialog->show();
    return dialog;
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
        QMessageBox ask(
            QMessageBox::Question, tr("ActiveTouch Workbench"),
            tr("%1 asks for more than a run should:\n%2\n\nRun it anyway?")
                .arg(QString::fromStdString(spec.name), QString::fromStdString(problem.problem)),
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
        QMessageBox ask(
            QMessageBox::Question, tr("ActiveTouch Workbench"),
            tr("%1 already holds a run. Replace it? Its files are removed first.").arg(dir),
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
    resetProgressToSeeds(first, last);
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

bool MainWindow::confirmComparison(const QString& otherPath, std::uint64_t first,
                                   std::uint64_t last) {
    const auto toRun = experimentToRun();
    if (!toRun || last < first) return false;
    const std::uint64_t seeds = last - first + 1;
    const RunPlan plan = planOf(*toRun).times(2.0 * double(seeds));
    QMessageBox ask(
        QMessageBox::Question, tr("Compare two experiments"),
        tr("Compare %1 (A, as shown) with %2 (B) on seeds %3-%4?\n\nThat is %5 whole runs on "
           "the simulated rig (%6 seeds, each in both experiments; about %7 taps), %8 at a "
           "time; Cancel (Esc) stops it and keeps the seeds finished. (The seeds are set in the "
           "Compare tab, beside its button.)")
            .arg(QString::fromStdString(toRun->name), QFileInfo(otherPath).fileName())
            .arg(first)
            .arg(last)
            .arg(2 * seeds)
            .arg(seeds)
            .arg(QLocale().toString(plan.taps(), 'f', 0))
            .arg(defaultSeedJobs()),
        QMessageBox::Yes | QMessageBox::No, this);
    ask.setObjectName("compareQuestion");
    ask.setDefaultButton(QMessageBox::Yes);
    if (ask.exec() != QMessageBox::Yes) {
        log(tr("comparison with %1 not started").arg(otherPath));
        return false;
    }
    return startComparison(otherPath, first, last);
}

bool MainWindow::startComparison(const QString& otherPath, std::uint64_t first,
                                 std::uint64_t last) {
    const auto toRun = experimentToRun();
    if (!toRun) return false;
    ExperimentSpec other;
    try {
        Json j;
        other = loadCheckedExperiment(otherPath.toStdString(), true, simulatedRigs(), &j);
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
    resetProgressToSeeds(first, last);
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
    sweeps_->showSeeds(sweepRates(rates->seeds));
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
    // Of recorded taps, none taken: an analysis, or a replay that also followed on them.
    const bool replay = r.rig.rfind("replay of ", 0) == 0;
    const bool analysis = replay || r.rig.rfind("recording ", 0) == 0;
    last_ = result;
    lastOutDir_ = dir;
    validation_->showRun(result);
    following_->showRun(result);
    recognition_->showRun(r);
    sweeps_->showRun(r, analysis);
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
        log(tr("validation: angle error %1°, position error %2 mm, %3")
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

void MainWindow::resetProgressToSeeds(std::uint64_t first, std::uint64_t last) {
    progress_->setRange(0, static_cast<int>(std::min<std::uint64_t>(last - first + 1, INT_MAX)));
    progress_->setValue(0);
}

}  // namespace activetouch
