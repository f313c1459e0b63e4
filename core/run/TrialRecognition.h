#pragma once
// What a run's followed paths say once every trial has run: the angle errors along them, and
// each path named among the shapes followed, by the paper's rule, smoothed and at any pose.
#include "core/run/ExperimentRun.h"

namespace activetouch {

/// The taps of every path whose angle error could be judged, and their median.
void summarisePathAngles(RunResult& result);

/// Makes the templates (one per distinct object followed, and one per shape in its own frame)
/// and names every path of the experiment's recognition mode with each rule, with the rates and
/// the median turn and place errors of the paths named rightly at any pose.
void recogniseTrialPaths(RunResult& result);

}  // namespace activetouch
