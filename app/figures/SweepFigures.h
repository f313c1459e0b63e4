#pragma once
// The accuracy-versus-time plots (docs/accuracy-vs-time.md), each with the paper's operating point
// marked.
class QCustomPlot;

namespace activetouch {

struct RunResult;
struct SweepRates;

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

/// Sweep (a) over seeds: angle and position error against mean taps per decision, each point the
/// mean over seeds with its 95 % interval both ways, the paper's single tap starred.
bool buildPerceptionSweepOverSeedsFigure(QCustomPlot& plot, const SweepRates& rates);
/// Sweep (b) over seeds as a trade-off: completion and contour distance against robot time per
/// completion, every setting a point with its intervals, the Pareto front joined, the paper's
/// setting starred and the settings that beat it named.
bool buildFollowingParetoFigure(QCustomPlot& plot, const SweepRates& rates);

/// (e) over seeds: active completion and recognition (the paper's rule, of the trials run) for
/// the fault-free run and each fault, with their 95 % intervals, one point per fault.
bool buildRobustnessFigure(QCustomPlot& plot, const SweepRates& rates);

}  // namespace activetouch
