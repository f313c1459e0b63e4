#pragma once
// The calibration figure (docs/calibration.md): Figure 6 recorded beside Figure 6 simulated with
// the fitted scene (the errors by position across the edge, the simulated recordings' mean with
// their least-to-largest band), and each taxel's recorded readings against the fitted scene's.
#include "devices/simulated/SceneFit.h"

class QCustomPlot;

namespace activetouch {

/// Draws the fit's figure into `plot`; false if the fit has nothing to show.
bool buildCalibrationFigure(QCustomPlot& plot, const SceneFit& fit,
                            const Figure6Comparison& figure6);

}  // namespace activetouch
