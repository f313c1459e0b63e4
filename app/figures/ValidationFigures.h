#pragma once
// The paper's Figure 5 (taps across each edge) and Figure 6 (angle and position errors per
// orientation x position, and their averages over orientations with the valid range marked),
// built into a QCustomPlot for the GUI or for export.
#include <QString>

class QCustomPlot;

namespace activetouch {

struct RunResult;

/// What a figure's title adds when the classifier is not the paper's, so that exported figures of
/// two classifiers cannot be mistaken for each other: "; kernel 2.5 bins" for a kernel-smoothed
/// likelihood, and for figures of following (`following`) "; trained on all 5 data sets" when the
/// trials followed with a classifier trained again after validation
/// (RunResult::classifierRetrainedOnTaps). Empty for the paper's.
QString classifierTitleNote(const RunResult& result, bool following);

/// Figure 5: data set 1's taps across each edge, one panel per orientation, pressures normalised
/// to a maximum of one, one colour per taxel.
void buildTapFigure(QCustomPlot& plot, const RunResult& result);

/// Figure 6: panels A, B heatmaps (fixed colour scales, no interpolation), C, D mean ± s.d. over
/// orientations, the valid range shaded; the statistics in a caption. Laid out for the plot's
/// shape when built: A and B side by side above C and D on a wide plot, one a row on a tall one.
void buildErrorFigure(QCustomPlot& plot, const RunResult& result);

/// The continuous percept's Figure 6 (runs that validate it): A, its median angle error per
/// trained orientation x position on the test taps; B, its median angle error on the following
/// taps against the true local edge, over the true edge angle (10 degree bins) x the tip's true
/// offset from the edge (1 mm bins), at any angle the trials met. False when the run has no
/// continuous validation.
bool buildContinuousAngleFigure(QCustomPlot& plot, const RunResult& result);

}  // namespace activetouch
