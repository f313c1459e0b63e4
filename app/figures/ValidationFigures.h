#pragma once
// The paper's Figure 5 (taps across each edge) and Figure 6 (angle and position errors per
// orientation x position, and their averages over orientations with the valid range marked),
// built into a QCustomPlot for the GUI or for export.
class QCustomPlot;

namespace activetouch {

struct RunResult;

/// Figure 5: data set 1's taps across each edge, one panel per orientation, pressures normalised
/// to a maximum of one, one colour per taxel.
void buildTapFigure(QCustomPlot& plot, const RunResult& result);

/// Figure 6: panels A, B heatmaps (fixed colour scales, no interpolation), C, D mean +- std over
/// orientations, the valid range shaded.
void buildErrorFigure(QCustomPlot& plot, const RunResult& result);

}  // namespace activetouch
