#pragma once
// The accuracy-versus-time plots (docs/accuracy-vs-time.md), each with the paper's operating point
// marked.
class QCustomPlot;

namespace activetouch {

struct RunResult;

/// The property on each plotted series of (a) and (b) that lists, per data point, the index of
/// its row in the run's sweep (sweeps.perception or sweeps.following), as a QVariantList of int:
/// what a click on a point picks.
inline constexpr const char* kSweepRowsProperty = "sweepRows";

/// (a) angle and position error against mean taps per decision, one point per belief threshold.
bool buildPerceptionSweepFigure(QCustomPlot& plot, const RunResult& result);
/// (b) completion and robot time per completed trial against follow step; time against path
/// error for every setting.
bool buildFollowingSweepFigure(QCustomPlot& plot, const RunResult& result);
/// (c) classifier error against microseconds per decision, one series per samples per tap.
bool buildComputeSweepFigure(QCustomPlot& plot, const RunResult& result);

}  // namespace activetouch
