#pragma once
// Accuracy costs time (docs/accuracy-vs-time.md): measured trade-offs.
//   (a) sequential perception: perception error vs mean taps per decision, over belief thresholds
//   (b) contour following: completion, path error, taps and robot time vs follow step,
//       repositioning step and belief threshold, active and passive
//   (c) compute: classifier error vs histogram bins and samples per tap, against microseconds
//       per decision
//   (d) a bandit learning the following setting by reward, set against (b)'s best
#include "core/run/ExperimentRun.h"
#include "core/run/SweepResults.h"

namespace activetouch {

/// Runs the experiment's sweeps using the trained result (its classifier, regions, valid range
/// and taps). Stops early, keeping the rows measured, when the run's observer asks to stop. With
/// `onTapsOnly`, only (c), which needs nothing but the taps taken (as for a recording: (a) takes
/// new taps and (b) follows contours, both on simulated rigs).
SweepResults runSweeps(const RunResult& trained, const RunOptions& options,
                       bool onTapsOnly = false);

/// The standard sweeps, those of experiments/accuracy_vs_time.json: (a) belief thresholds
/// 0.5-0.999 over 20 taps per class, (b) follow steps 1-4 mm x repositioning 0.5-2 mm x single
/// tap, 0.9 and 0.99, active and passive, 3 repeats, (c) 10-200 bins x 5-50 samples, (d) a
/// bandit of 144 trials, a completed contour worth 2000 robot seconds.
SweepSpec standardSweeps();

}  // namespace activetouch
