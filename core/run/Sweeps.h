#pragma once
// Accuracy costs time (docs/accuracy-vs-time.md): measured trade-offs.
//   (a) sequential perception: perception error vs mean taps per decision, over belief thresholds
//   (b) contour following: completion, path error, taps and robot time vs follow step,
//       repositioning step and belief threshold, active and passive
//   (c) compute: classifier error vs histogram bins and samples per tap, against microseconds
//       per decision
#include <string>
#include <vector>

#include "core/experiment/Experiment.h"

namespace activetouch {

struct RunResult;
struct RunOptions;

struct PerceptionSweepRow {
    double threshold;
    double meanTaps, angleError_deg, positionError_mm, correctFraction;
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

struct SweepResults {
    std::vector<PerceptionSweepRow> perception;
    std::vector<FollowingSweepRow> following;
    std::vector<ComputeSweepRow> compute;
    bool empty() const { return perception.empty() && following.empty() && compute.empty(); }
};

/// Runs the experiment's sweeps using the trained result (its classifier, regions, valid range
/// and taps). Stops early, keeping the rows measured, when options.cancel is set. With
/// `onTapsOnly`, only (c), which needs nothing but the taps taken (as for a recording: (a) takes
/// new taps and (b) follows contours, both on simulated rigs).
SweepResults runSweeps(const RunResult& trained, const RunOptions& options,
                       bool onTapsOnly = false);

}  // namespace activetouch
