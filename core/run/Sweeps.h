#pragma once
// Accuracy costs time (docs/accuracy-vs-time.md): measured trade-offs.
//   (a) sequential perception: perception error vs mean taps per decision, over belief thresholds
//   (b) contour following: completion, path error, taps and robot time vs follow step,
//       repositioning step and belief threshold, active and passive
//   (c) compute: classifier error vs histogram bins and samples per tap, against microseconds
//       per decision
#include "core/run/ExperimentRun.h"
#include "core/run/SweepResults.h"

namespace activetouch {

/// Runs the experiment's sweeps using the trained result (its classifier, regions, valid range
/// and taps). Stops early, keeping the rows measured, when the run's observer asks to stop. With
/// `onTapsOnly`, only (c), which needs nothing but the taps taken (as for a recording: (a) takes
/// new taps and (b) follows contours, both on simulated rigs).
SweepResults runSweeps(const RunResult& trained, const RunOptions& options,
                       bool onTapsOnly = false);

}  // namespace activetouch
