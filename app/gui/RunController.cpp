#include "app/gui/RunController.h"

#include <QDir>
#include <algorithm>
#include <chrono>
#include <climits>
#include <thread>

#include "app/figures/FollowingFigures.h"
#include "core/run/RunArtefacts.h"
#include "core/run/RunFolder.h"
#include "devices/simulated/SimulatedWorld.h"

namespace activetouch {

/// Hears a run's taps for the window: each tap into the live feed, paced as asked, and the
/// progress with an estimate of the time left; a cancel stops the run after the tap in flight.
class RunController::Observer final : public RunObserver {
public:
    Observer(RunController& controller, Pace pace, std::chrono::steady_clock::time_point started)
        : c_(controller), pace_(pace), started_(started) {}

    void progressed(const RunProgress& p) override {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
        const double left =
            p.tapsDone > 0 ? elapsed / p.tapsDone * std::max(0, p.tapsPlanned - p.tapsDone) : 0.0;
        emit c_.progress(p.tapsDone, p.tapsPlanned, QString::fromStdString(p.step), left);
    }

    void tapTaken(const TapRecord& r, const std::string& what, Stage stage) override {
        c_.live_.publishTap(r, QString::fromStdString(what), stage == Stage::Following);
        if (pace_ == Pace::Fastest) return;  // the live view replays the newest tap
        // Pace the frames as the fingertip streams them; stop within a frame on cancel.
        for (int s = 0; s < r.tap.sampleCount() && !c_.cancel_; ++s) {
            c_.live_.publishFrame(r.tap.frame(s), r.tap.taxels);
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        if (pace_ == Pace::RobotTime) {
            const auto settle = std::chrono::duration<double>(
                std::max(0.0, r.cycleTime_s - r.tap.sampleCount() * 0.02));
            const auto until = std::chrono::steady_clock::now() + settle;
            while (!c_.cancel_ && std::chrono::steady_clock::now() < until)
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
    }

    bool stopRequested() const override { return c_.cancel_.load(); }

private:
    RunController& c_;
    Pace pace_;
    std::chrono::steady_clock::time_point started_;
};

namespace {
/// The seeds a run over seeds has done, and how long the rest will take at the pace so far.
struct SeedClock {
    SeedClock(std::uint64_t first, std::uint64_t last)
        : planned(static_cast<int>(std::min<std::uint64_t>(last - first + 1, INT_MAX))) {}
    /// One more seed done; returns the seconds the rest will take.
    double tick() {
        ++done;
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        return elapsed / done * (planned - done);
    }
    const std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
    const int planned;
    int done = 0;
};
}  // namespace

RunController::RunController(LiveFeed& live, QObject* parent) : QObject(parent), live_(live) {
    qRegisterMetaType<std::shared_ptr<const RunResult>>();
    qRegisterMetaType<std::shared_ptr<const SeedRates>>();
    qRegisterMetaType<SeedOutcome>();
    qRegisterMetaType<std::vector<PairedTrial>>();
    qRegisterMetaType<std::shared_ptr<const PairedComparison>>();
}

RunController::~RunController() {
    if (!thread_) return;
    // The run refers to this controller and to the live feed, so it must end before they go.
    // By the device-thread policy (docs/design.md §2) it does, soon: it stops after the tap in
    // flight, and every device call it can be inside has a bound of its own (a tap's deadline is
    // seconds; an interrupted stage move ends at once). Once finished, the thread is ours to
    // delete: its finished slot will not run after this. It is never destroyed running or left
    // to run on.
    cancel_ = true;
    thread_->wait();
    delete thread_;
}

void RunController::cancel() {
    cancel_ = true;
}

bool RunController::stopAndWait(int ms) {
    if (!thread_) return true;
    cancel_ = true;
    return thread_->wait(QDeadlineTimer(ms));
}

bool RunController::start(const ExperimentSpec& specIn, const QString& outDir, What what, Pace pace,
                          std::shared_ptr<const RunResult> trained,
                          std::shared_ptr<const ConnectedRig> connected,
                          std::shared_ptr<const RecordedRun> recorded) {
    if (thread_) {
        emit failed(tr("A run is already going; cancel it or wait for it to finish."));
        return false;
    }
    if (what == What::FollowingOnly && (!trained || !trained->classifier.trained())) {
        emit failed(tr("Following needs a trained classifier: run training and validation first."));
        return false;
    }
    if (what == What::FollowingOnly && !recorded) {
        // Following alone uses the classifier the last run trained; settings that would train
        // another one must not be shown as if they were followed with.
        if (const auto changed = trainingSettingsChanged(*trained, specIn); !changed.empty()) {
            QStringList lines;
            for (const auto& c : changed) lines << QString::fromStdString(c);
            emit failed(tr("Run following follows with the classifier the last run trained, and "
                           "the experiment as shown would train another (%1). Run training & "
                           "validation, or the whole protocol, to train with these settings.")
                            .arg(lines.join("; ")));
            return false;
        }
    }
    ExperimentSpec spec = specIn;
    if (what == What::TrainingOnly) spec.trials.clear();
    if (connected) {
        try {
            checkRunnableOn(spec, *connected);
        } catch (const std::exception& e) {
            emit failed(tr("This run cannot take place on the connected rig: %1").arg(e.what()));
            return false;
        }
        pace = Pace::Fastest;  // real devices keep their own time
    }
    if (recorded && (connected || what == What::FollowingOnly)) {
        emit failed(
            tr("A recording is analysed or replayed on its own: its taps train and validate "
               "(and a replay's follow), with no devices."));
        return false;
    }
    launch(outDir, [this, spec, outDir, what, pace, trained, connected, recorded]() mutable {
        const auto started = std::chrono::steady_clock::now();
        RunOptions options;
        options.simulated = &simulatedRigs();
        options.outDir = outDir.toStdString();
        options.connected = connected.get();
        if (recorded) {
            options.recordedTaps = &recorded->taps;
            if (recorded->replay()) options.recordedTrials = &recorded->trials;
            options.recordingName = recorded->name;
        }
        Observer observer(*this, pace, started);
        options.observer = &observer;
        try {
            // The window asked before replacing a run in the folder (MainWindow::mayWriteRun).
            const RunFolderClaim claim(
                options.outDir, recorded ? (recorded->replay() ? "replay" : "analyse") : "run",
                spec.name, runFactsOf(spec, recorded ? &recorded->taps : nullptr), true);
            auto result = std::make_shared<RunResult>(what == What::FollowingOnly
                                                          ? runFollowing(*trained, spec, options)
                                                          : runExperiment(spec, options));
            writeRunArtefacts(*result, options.outDir, started);
            connected.reset();  // the devices are free again before anyone hears of the end
            emit finished(result, outDir);
        } catch (const std::exception& e) {
            connected.reset();
            emit failed(tr("The run stopped: %1. Every tap taken so far is in %2/data.")
                            .arg(QString::fromStdString(e.what()), outDir));
        }
    });
    return true;
}

bool RunController::canRunSeeds(std::uint64_t first, std::uint64_t last) {
    if (thread_) {
        emit failed(tr("A run is already going; cancel it or wait for it to finish."));
        return false;
    }
    if (first > last) {
        emit failed(tr("The first seed (%1) is after the last (%2); give the first seed first.")
                        .arg(first)
                        .arg(last));
        return false;
    }
    return true;
}

bool RunController::startSeeds(const ExperimentSpec& spec, std::uint64_t first, std::uint64_t last,
                               const QString& outDir) {
    if (!canRunSeeds(first, last)) return false;
    launch(outDir, [this, spec, first, last, outDir] {
        SeedClock clock(first, last);
        try {
            const RunFolderClaim claim(outDir.toStdString(), "seeds", spec.name, runFactsOf(spec),
                                       true);
            auto rates = std::make_shared<SeedRates>(runSeeds(
                simulatedRigs(), spec, first, last, outDir.toStdString(),
                [&](const SeedOutcome& o) {
                    emit seedFinished(o);
                    const double left = clock.tick();
                    emit progress(clock.done, clock.planned,
                                  tr("seed %1 of %2-%3 finished").arg(o.seed).arg(first).arg(last),
                                  left);
                    return !cancel_;
                }));
            const bool cancelled = rates->seeds.size() < last - first + 1;
            emit seedsFinished(rates, outDir, cancelled);
        } catch (const std::exception& e) {
            emit failed(tr("The seeds run stopped: %1. The seeds finished so far are in "
                           "%2/rates.csv.")
                            .arg(QString::fromStdString(e.what()), outDir));
        }
    });
    return true;
}

bool RunController::startComparison(const ExperimentSpec& a, const ExperimentSpec& b,
                                    std::uint64_t first, std::uint64_t last,
                                    const QString& outDir) {
    if (!canRunSeeds(first, last)) return false;
    launch(outDir, [this, a, b, first, last, outDir] {
        SeedClock clock(first, last);
        try {
            const RunFolderClaim claim(outDir.toStdString(), "compare", a.name, runFactsOf(a),
                                       true);
            auto comparison = std::make_shared<PairedComparison>(comparePaired(
                simulatedRigs(), a, b, first, last, outDir.toStdString(),
                [&](std::uint64_t seed, const std::vector<PairedTrial>& pairs,
                    const PairedComparison& soFar) {
                    emit comparisonSeedFinished(quint64(seed), pairs,
                                                std::make_shared<const PairedComparison>(soFar));
                    const double left = clock.tick();
                    emit progress(clock.done, clock.planned,
                                  tr("seed %1 of %2-%3 compared").arg(seed).arg(first).arg(last),
                                  left);
                    return !cancel_;
                }));
            const bool cancelled = std::uint64_t(comparison->seeds) < last - first + 1;
            emit comparisonFinished(comparison, outDir, cancelled);
        } catch (const std::exception& e) {
            emit failed(tr("The comparison stopped: %1. The seeds compared so far are in "
                           "%2/compare.csv.")
                            .arg(QString::fromStdString(e.what()), outDir));
        }
    });
    return true;
}

bool RunController::startTrialPair(const ExperimentSpec& a, const ExperimentSpec& b,
                                   std::uint64_t seed, FollowingMode mode, const std::string& label,
                                   int trial, const QString& outDir) {
    if (!canRunSeeds(seed, seed)) return false;
    launch(outDir, [this, a, b, seed, mode, label, trial, outDir] {
        emit progress(0, 1,
                      tr("seed %1: %2 trial %3 of %4 in both experiments")
                          .arg(seed)
                          .arg(modeName(mode))
                          .arg(trial)
                          .arg(QString::fromStdString(label)),
                      0.0);
        try {
            auto pair = std::make_shared<const TrialPairRun>(
                runTrialPair(simulatedRigs(), a, b, seed, mode, label, trial));
            emit progress(1, 1, tr("seed %1 run in both experiments").arg(seed), 0.0);
            emit trialPairFinished(pair, outDir);
        } catch (const std::exception& e) {
            emit failed(tr("Could not run the trial in both experiments: %1")
                            .arg(QString::fromStdString(e.what())));
        }
    });
    return true;
}

template <typename Work>
void RunController::launch(const QString& outDir, Work work) {
    cancel_ = false;
    thread_ = QThread::create(std::move(work));
    connect(thread_, &QThread::finished, this, [this] {
        thread_->deleteLater();
        thread_ = nullptr;
        emit idle();
    });
    if (!outDir.isEmpty()) QDir().mkpath(outDir);
    thread_->start();
}

}  // namespace activetouch
