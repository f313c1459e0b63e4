#pragma once
// The perception sweep of runSweeps() (Sweeps.h). Internal to core/run.
#include <vector>

#include "core/run/ExperimentRun.h"
#include "core/run/SweepResults.h"

namespace activetouch {

/// Decisions at each of the experiment's belief thresholds on fresh repeated taps of every
/// class, each class's repeats taken in turn from each starting tap; the single tap's row (its
/// most likely class) into `singleTap` and the belief's calibration on these taps into
/// `calibration`.
std::vector<PerceptionSweepRow> perceptionSweep(const RunResult& r, const RunOptions& options,
                                                PerceptionSweepCalibration& calibration,
                                                PerceptionSweepRow& singleTap);

}  // namespace activetouch
