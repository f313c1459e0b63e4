#pragma once
// What an experiment asks of the rig before any tap: how many taps, how much robot time and how
// much memory the taps it keeps will take. A plan beyond the bounds below is refused unless the
// user says it is meant (activetouch-cli --allow-long-plan), since a mistyped count can ask for
// years of robot time (docs/limits.md).
#include <cstdint>
#include <string>

#include "core/experiment/Experiment.h"

namespace activetouch {

/// Counts are doubles: a plan is compared with its bounds before anything is sized from it, so
/// no product of counts can overflow on the way.
struct RunPlan {
    double trainingTaps = 0;  ///< training and test taps, exact
    double trialTaps = 0;     ///< contour-following taps, estimated (a perimeter's worth a trial)
    double sweepTaps = 0;     ///< taps the accuracy-versus-time sweeps take, estimated
    /// Estimated, at the scene's tap cycle and stage speed, for the taps a rig takes: the sweeps
    /// always run on simulated rigs and take none of it.
    double robotTime_s = 0;
    double heldTapBytes = 0;  ///< the training and test taps a run keeps in memory
    double taps() const { return trainingTaps + trialTaps + sweepTaps; }
    /// The same plan repeated `runs` times (seeds, or both sides of a comparison).
    RunPlan times(double runs) const;
};

inline constexpr double kMaxPlannedRobotTime_s = 24.0 * 3600.0;
inline constexpr double kMaxPlannedTaps = 1e7;
inline constexpr double kMaxHeldTapBytes = 2.0 * 1024 * 1024 * 1024;

RunPlan planOf(const ExperimentSpec& spec);

/// "2,400 training and test taps, about 1,310 following taps; about 3.1 h of robot time".
std::string planText(const RunPlan& plan);

/// Why the plan is beyond the bounds (naming the part of the file that asks for most of it, as
/// `place`), or empty. Every plan is held to the taps and memory bounds; the robot-time bound
/// holds where the taps are taken on a rig (`onRig`): simulated robot time costs nothing.
struct PlanProblem {
    std::string place, problem;
    bool empty() const { return problem.empty(); }
};
PlanProblem planProblem(const RunPlan& plan, const std::string& what = "the experiment",
                        bool onRig = false);

}  // namespace activetouch
