#pragma once
// Runs experiments off the GUI thread: progress with taps done and time left, cancel that stops
// within one tap and keeps every tap taken, and a clear final state. The GUI thread never waits
// on the rig.
#include <QObject>
#include <QThread>
#include <atomic>
#include <memory>

#include "app/gui/LiveFeed.h"
#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedRates.h"
#include "core/run/ExperimentRun.h"
#include "core/run/RecordedRuns.h"

namespace activetouch {

enum class Pace {
    Fastest,     ///< as fast as the simulation goes; the live view shows the latest tap
    LiveFrames,  ///< each tap's frames at 50 Hz (1 s per tap), no settle pauses
    RobotTime,   ///< the robot's own timing: frames at 50 Hz and the settle pause
};

class RunController : public QObject {
    Q_OBJECT
public:
    explicit RunController(LiveFeed& live, QObject* parent = nullptr);
    ~RunController() override;

    enum class What { Everything, TrainingOnly, FollowingOnly };

    /// Starts a run writing into `outDir`, on the simulated rig or on `connected` (held until the
    /// run ends; the pace is then the devices' own), or an analysis of `recorded` taps (training
    /// and validation only, the taps shown at `pace`); false (and failed()) if one is already
    /// running, FollowingOnly has no trained classifier to use, or the experiment cannot run on
    /// the connected rig.
    bool start(const ExperimentSpec& spec, const QString& outDir, What what, Pace pace,
               std::shared_ptr<const RunResult> trained = {},
               std::shared_ptr<const ConnectedRig> connected = {},
               std::shared_ptr<const RecordedRun> recorded = {});
    /// Starts running `spec` once per seed from `first` to `last` on the simulated rig, each a
    /// whole run, writing <outDir>/rates.csv seed by seed and rates.json at the end; cancel
    /// stops after the seed in flight and keeps every finished seed. False (and failed()) if a
    /// run is already going or the range is backwards.
    bool startSeeds(const ExperimentSpec& spec, std::uint64_t first, std::uint64_t last,
                    const QString& outDir);
    /// Starts comparing `a` and `b` trial by trial on the seeds `first` to `last` (each a whole
    /// run of each on the simulated rig), writing <outDir>/compare.csv seed by seed and
    /// compare.json at the end; cancel stops after the seed in flight. False (and failed()) as
    /// for startSeeds.
    bool startComparison(const ExperimentSpec& a, const ExperimentSpec& b, std::uint64_t first,
                         std::uint64_t last, const QString& outDir);
    /// Runs one trial of `seed` as `a` and as `b` ran it in a comparison (runTrialPair: a whole
    /// run of each on the simulated rig), to see where they part; trialPairFinished hands it on
    /// with `outDir`, the comparison's folder, where its table and figure go. False (and
    /// failed()) if a run is going.
    bool startTrialPair(const ExperimentSpec& a, const ExperimentSpec& b, std::uint64_t seed,
                        FollowingMode mode, const std::string& label, int trial,
                        const QString& outDir);
    void cancel();
    bool running() const { return thread_ != nullptr; }
    /// Asks a running run to stop and waits at most `ms` for it; true if it stopped.
    bool stopAndWait(int ms);

signals:
    void progress(int tapsDone, int tapsPlanned, const QString& step, double secondsLeft);
    void finished(std::shared_ptr<const activetouch::RunResult> result, const QString& outDir);
    void failed(const QString& message);
    /// A seed of a seeds run has finished.
    void seedFinished(const activetouch::SeedOutcome& outcome);
    /// A seeds run has ended, with every seed finished (all planned unless cancelled).
    void seedsFinished(std::shared_ptr<const activetouch::SeedRates> rates, const QString& outDir,
                       bool cancelled);
    /// A seed of a comparison has finished: its paired trials, and the comparison so far.
    void comparisonSeedFinished(quint64 seed, const std::vector<activetouch::PairedTrial>& pairs,
                                std::shared_ptr<const activetouch::PairedComparison> soFar);
    /// A comparison has ended, with every seed finished (all planned unless cancelled).
    void comparisonFinished(std::shared_ptr<const activetouch::PairedComparison> comparison,
                            const QString& outDir, bool cancelled);
    /// A trial pair has been run.
    void trialPairFinished(std::shared_ptr<const activetouch::TrialPairRun> pair,
                           const QString& outDir);
    /// The worker has ended (after finished or failed): a new run may start.
    void idle();

private:
    /// False (and failed()) if a run is going or the seeds run backwards.
    bool canRunSeeds(std::uint64_t first, std::uint64_t last);
    /// Runs `work` on a new worker thread; idle() when it ends.
    template <typename Work>
    void launch(const QString& outDir, Work work);

    class Observer;  // the run's taps into the live feed and the progress signal

    LiveFeed& live_;
    QThread* thread_ = nullptr;
    std::atomic<bool> cancel_{false};
};

}  // namespace activetouch

Q_DECLARE_METATYPE(std::shared_ptr<const activetouch::RunResult>)
Q_DECLARE_METATYPE(std::shared_ptr<const activetouch::SeedRates>)
Q_DECLARE_METATYPE(activetouch::SeedOutcome)
Q_DECLARE_METATYPE(std::vector<activetouch::PairedTrial>)
Q_DECLARE_METATYPE(std::shared_ptr<const activetouch::PairedComparison>)
Q_DECLARE_METATYPE(std::shared_ptr<const activetouch::TrialPairRun>)
