#pragma once
// The accuracy-versus-time sweeps over many seeds (docs/accuracy-vs-time.md, "Over seeds"). One
// seed is a whole run: its own training, calibration, sweep taps and following trials, so the
// seeds are the independent units. Each figure is the mean over seeds with a 95 % interval over
// seeds; sweep (b)'s settings are set against the paper's, paired seed by seed, and the settings
// on the trade-off's Pareto front are named.
#include <limits>
#include <string>
#include <vector>

#include "core/io/OutputFile.h"
#include "core/analysis/SeedRates.h"
#include "core/run/SweepRecords.h"
#include "core/run/SweepResults.h"

namespace activetouch {

/// A verdict against the paper's setting.
enum class PaperVerdict { NotEnoughSeeds, DoesNotBeat, Beats };
/// The fewest paired seeds a verdict against the paper's setting rests on.
inline constexpr int kMinVerdictSeeds = 20;

/// A mean over seeds with its 95 % interval (Student's t over the seeds' values). A quantity with
/// a range [least, most] has its interval computed where it cannot leave that range (the logit
/// of its place in a two-sided range, the log of its distance from a lower bound, by the delta
/// method) rather than cut at the bound. With one seed the interval is the whole range; with
/// none, all zero.

SweepEstimate overSeeds(const std::vector<double>& perSeed,
                        double least = -std::numeric_limits<double>::infinity(),
                        double most = std::numeric_limits<double>::infinity());

/// One threshold of sweep (a) over seeds: each figure the mean of the seeds' means.
struct PerceptionOverSeeds {
    double threshold = 0.0;  ///< 0: the paper's single tap
    int seeds = 0;
    SweepEstimate taps, robotTime_s, angle_deg, position_mm, correct;
    SweepEstimate angleFall_deg, positionFall_mm;  ///< below the single tap, paired in each seed
    SweepEstimate planeRecognised, airRecognised;
};

/// One setting of sweep (b) over seeds.
struct FollowingOverSeeds {
    FollowingMode mode = FollowingMode::Active;
    double followStep_mm = 0, repositionStep_mm = 0, beliefThreshold = 0;
    bool paperSetting = false;
    int seeds = 0;
    Rate completed;  ///< over every trial of every seed, Wilson interval
    SweepEstimate contourDistance_mm, robotTimePerTrial_s, tapsPerTrial;
    /// All robot time spent over all seeds / trials completed (infinite if none), with a 95 %
    /// interval from resampling the seeds.
    SweepEstimate robotTimePerCompletion_s;
    /// Against the paper's setting of the same mode, seed by seed: completion (percentage
    /// points, this minus the paper's), robot time per completion (this / the paper's, from
    /// resampling the seeds) and contour distance (this minus the paper's).
    bool paired = false;
    SweepEstimate completionDifference_points, timeRatio, distanceDifference_mm;
    bool onParetoFront = false;  ///< no other setting is as fast, as complete and as close
    int pairedSeeds = 0;         ///< seeds where both this and the paper's setting ran trials
    PaperVerdict verdict = PaperVerdict::NotEnoughSeeds;
    bool beatsPaper = false;     ///< verdict Beats: faster than the paper's at no loss of completion
};

/// Whether a setting beats the paper's: given only on enough seeds for its intervals to say
/// something (kMinVerdictSeeds paired seeds, and a completion difference and time ratio whose
/// intervals have width); then Beats if the time ratio's interval lies below 1 and the
/// completion difference's above -kCompletionMargin_points.
PaperVerdict paperVerdict(const FollowingOverSeeds& f);

/// Sweep (c) at one setting over seeds.
struct ComputeOverSeeds {
    int bins = 0, samples = 0;
    bool paperSetting = false;
    SweepEstimate angle_deg, position_mm, microsecondsPerDecision;
};

/// (d) over seeds: how often the bandit chose (b)'s best setting of the same seed, what its
/// choice lost against that best by (b)'s own measure, and what it spent.
struct BanditOverSeeds {
    int seeds = 0, choseBest = 0;
    double completionWorth_s = 0;
    SweepEstimate regret;  ///< best reward minus the chosen setting's, per trial
    /// The same over seeds: the pooled reward of each seed's chosen setting against the best
    /// setting over all seeds, both from (b) over seeds.
    SweepEstimate pooledRegret;
    double robotTime_s = 0, sweepRobotTime_s = 0;  ///< summed over seeds
    /// How often each setting was chosen, most chosen first: (b)'s row and the count.
    std::vector<std::pair<int, int>> choices;
    int pooledBest = -1;  ///< (b)'s row with the highest pooled reward
};

/// (e) One fault over seeds: its rates, and how far they fall below the fault-free run of the
/// same seed (paired, percentage points, Student's t over seeds).
struct RobustnessOverSeeds {
    std::string fault;
    int seeds = 0, failedRuns = 0;
    Rate completed, recognisedRaw, recognisedAnyPose;
    SweepEstimate completionFall_points, recognitionFall_points, angleError_deg;
};

struct SweepRates {
    int seeds = 0;  ///< runs whose sweeps were measured
    std::vector<PerceptionOverSeeds> perception;
    PerceptionOverSeeds perceptionSingleTap;
    int calibrationSeeds = 0, calibrationWithin005 = 0;
    SweepEstimate eceRaw, eceCalibrated, eceIfCalibrated;
    std::vector<FollowingOverSeeds> following;
    std::vector<ComputeOverSeeds> compute;
    BanditOverSeeds bandit;
    RobustnessOverSeeds robustnessBase;
    std::vector<RobustnessOverSeeds> robustness;
    bool empty() const {
        return perception.empty() && following.empty() && compute.empty() && robustness.empty();
    }
};

/// A non-inferiority margin: a setting beats the paper's only if the lower end of its paired
/// completion difference is above minus this many percentage points.
constexpr double kCompletionMargin_points = 2.0;

/// The sweeps of the runs in `seeds` that measured them (a failed run measured none) over seeds.
/// The settings are matched by position, which is the same for every seed of one experiment.
SweepRates sweepRates(const std::vector<SeedOutcome>& seeds);

Json sweepRatesJson(const SweepRates& rates);

/// Writes sweeps_perception.csv, sweeps_following.csv, sweeps_compute.csv and
/// sweeps_robustness.csv (those that have rows) in `dir`.
void writeSweepRateTables(const SweepRates& rates, const std::string& dir);

/// The tables as text for a terminal: (a), the calibration, (b) with the front and the settings
/// that beat the paper's, (c).
std::vector<std::string> describeSweepRates(const SweepRates& rates);

}  // namespace activetouch
