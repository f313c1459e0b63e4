#pragma once
// What the accuracy-versus-time sweeps measure (docs/accuracy-vs-time.md), as a run keeps it:
// a row per setting of each sweep. The sweeps themselves run in core/run/Sweeps.h.
#include <vector>

#include "core/control/FollowingSettings.h"

namespace activetouch {

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

}  // namespace activetouch
