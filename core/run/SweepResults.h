#pragma once
// What the accuracy-versus-time sweeps measure (docs/accuracy-vs-time.md), as a run keeps it:
// a row per setting of each sweep. The sweeps themselves run in core/run/Sweeps.h.
#include <string>
#include <vector>

#include "core/control/FollowingSettings.h"

namespace activetouch {

/// A mean over a sweep's decisions with its 95 % interval. Decisions about one class share taps,
/// so the interval treats the classes as the independent units: mean +- 1.96 x the standard
/// error of the per-class means.
struct SweepEstimate {
    double mean = 0.0, low = 0.0, high = 0.0;
};

struct PerceptionSweepRow {
    double threshold = 0.0;
    int decisions = 0;
    /// Over every decision (angle over edge classes only: plane and air have no orientation).
    double meanTaps = 0, angleError_deg = 0, positionError_mm = 0, correctFraction = 0;
    double meanRobotTime_s = 0;  ///< the taps' cycle times per decision
    SweepEstimate taps, robotTime_s, angle_deg, position_mm, correct;
    /// How much lower the edge angle and position errors are than with single-tap decisions
    /// (the paper's operating point), paired decision by decision (the same class and starting
    /// tap), with the interval over classes.
    SweepEstimate angleFall_deg, positionFall_mm;
    /// Decisions whose truth is a plane (air) class, and how many of them were perceived as
    /// plane (air): their orientation cannot be told, so they are reported as recognised or not.
    int planeDecisions = 0, airDecisions = 0;
    double planeRecognised = 0, airRecognised = 0;
};

/// How well one tap's belief is calibrated on the perception sweep's fresh taps, which neither
/// trained the classifier nor fitted the calibration.
struct PerceptionSweepCalibration {
    bool measured = false;
    bool calibrated = false;  ///< the sweep's decisions used the run's calibrated belief
    int taps = 0;
    double eceRaw = 0, eceCalibrated = 0, eceIfCalibrated = 0;
};

struct FollowingSweepRow {
    FollowingMode mode;
    double followStep_mm, repositionStep_mm, beliefThreshold;
    int trials = 0, completed = 0;
    double meanContourDistance_mm = 0, meanTaps = 0, meanRobotTime_s = 0;
    double robotTimePerCompletion_s = 0;  ///< all robot time spent / trials completed (inf if none)
    bool paperSetting = false;            ///< 2 mm follow, 1 mm reposition, single tap
};

struct ComputeSweepRow {
    int bins, samples;
    double angleError_deg, positionError_mm, microsecondsPerDecision;
    bool paperSetting = false;  ///< 100 bins, 50 samples
};

/// One setting the bandit could choose: (b)'s active setting at `sweepRow`.
struct BanditArm {
    int sweepRow = -1;
    double followStep_mm = 0, repositionStep_mm = 0, beliefThreshold = 0;
    int pulls = 0, completed = 0;
    double rewardSum = 0, robotTime_s = 0;
    double meanReward() const { return pulls > 0 ? rewardSum / pulls : 0.0; }
};

/// (d) The operating point learnt by reward: UCB1 over (b)'s active settings, each trial's
/// reward 1 if it completed, less its robot time over completionWorth_s. Its choice (the setting
/// it ran most) is set against (b)'s best by the same reward.
struct BanditResult {
    bool ran = false;
    double completionWorth_s = 0;
    int rounds = 0;
    std::vector<BanditArm> arms;
    int chosen = -1;     ///< arm the learner ran most (ties: the higher mean reward)
    int sweepBest = -1;  ///< arm whose (b) row has the highest mean reward
    /// The mean reward per trial of the chosen and the best arm, both as (b) measured them.
    double chosenSweepReward = 0, bestSweepReward = 0;
    double robotTime_s = 0;       ///< what the learner spent
    double sweepRobotTime_s = 0;  ///< what (b)'s active settings spent
};

/// The bandit's reward for one trial.
inline double banditReward(bool completed, double robotTime_s, double completionWorth_s) {
    return (completed ? 1.0 : 0.0) - robotTime_s / completionWorth_s;
}

/// (e) One run of the experiment on the same seed with one fault added to the scene, or the run
/// itself (the fault-free base).
struct RobustnessRow {
    std::string fault;    ///< "none" for the base
    std::string failure;  ///< the device or rig error that stopped the run, if one did
    int activeTrials = 0, activeCompleted = 0;
    int recognitionTrials = 0, recognisedRaw = 0, recognisedAnyPose = 0;
    double angleError_deg = 0, positionError_mm = 0;  ///< its offline validation
};

struct SweepResults {
    std::vector<PerceptionSweepRow> perception;
    PerceptionSweepCalibration perceptionCalibration;
    /// The paper's operating point on the same taps and axes: one tap, its most likely class.
    PerceptionSweepRow perceptionSingleTap;
    std::vector<FollowingSweepRow> following;
    std::vector<ComputeSweepRow> compute;
    BanditResult bandit;
    RobustnessRow robustnessBase;
    std::vector<RobustnessRow> robustness;
    bool empty() const {
        return perception.empty() && following.empty() && compute.empty() && robustness.empty();
    }
};

}  // namespace activetouch
