#include "app/figures/CalibrationFigures.h"

#include <algorithm>

#include "app/figures/FigureLayout.h"
#include "qcustomplot.h"

namespace activetouch {

bool buildCalibrationFigure(QCustomPlot& plot, const SceneFit& fit,
                            const Figure6Comparison& figure6) {
    int matching = 0;
    for (const auto& t : fit.taxels) matching += t.matches;
    startFigure(
        plot,
        QString("Calibration: the recording against %1 recordings simulated with the fitted scene")
            .arg(figure6.simulated.size()),
        QString(
            "%1 taps, %2 samples over nothing. Figure 6 recorded: angle %3 deg, position %4 mm;\n"
            "simulated: angle %5 (%6 to %7) deg, position %8 (%9 to %10) mm. %11 of %12 "
            "taxels match (Kolmogorov-Smirnov within the largest of ten simulated pairs).")
            .arg(fit.taps)
            .arg(fit.nothingSamples)
            .arg(figure6.recorded.angleError_deg, 0, 'f', 1)
            .arg(figure6.recorded.positionError_mm, 0, 'f', 2)
            .arg(figure6.angleMean, 0, 'f', 1)
            .arg(figure6.angleLeast, 0, 'f', 1)
            .arg(figure6.angleLargest, 0, 'f', 1)
            .arg(figure6.positionMean, 0, 'f', 2)
            .arg(figure6.positionLeast, 0, 'f', 2)
            .arg(figure6.positionLargest, 0, 'f', 2)
            .arg(matching)
            .arg(fit.taxels.size()));
    if (fit.taxels.empty() || figure6.simulated.empty()) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    // Figure 6 by position: the recording, and the simulated recordings' mean and range.
    const std::size_t positions = figure6.recorded.angleMean.size();
    auto byPosition = [&](int column, const QString& title, const QString& unit, auto get) {
        const auto [rect, legend] = addTitledPanelWithLegendBelow(
            grid, 0, column, 2, title, "position across the edge (class)", unit);
        RunningValue simulated;
        QVector<double> x, recorded;
        for (std::size_t p = 0; p < positions; ++p) {
            double mean = 0, lo = 1e300, hi = -1e300;
            for (const auto& v : figure6.simulated) {
                const double e = get(v)[p];
                mean += e / static_cast<double>(figure6.simulated.size());
                lo = std::min(lo, e);
                hi = std::max(hi, e);
            }
            simulated.append(double(p + 1), mean, lo, hi);
            x << double(p + 1);
            recorded << get(figure6.recorded)[p];
        }
        addRunningBand(rect, legend, "simulated, fitted scene (least to largest)", simulated,
                       seriesColour(1));
        addSeries(rect, legend, "recorded", x, recorded, seriesColour(0));
        rect->axis(QCPAxis::atBottom)->setRange(0.5, double(positions) + 0.5);
        integerTicks(rect->axis(QCPAxis::atBottom), positions > 12 ? 3.0 : 1.0);
        rect->axis(QCPAxis::atLeft)->rescale();
        rect->axis(QCPAxis::atLeft)->setRangeLower(0);
    };
    byPosition(0, "edge angle error", "deg",
               [](const ValidationResult& v) -> const std::vector<double>& { return v.angleMean; });
    byPosition(
        1, "position error", "mm",
        [](const ValidationResult& v) -> const std::vector<double>& { return v.positionMean; });
    // Each taxel's readings: the distance from the fitted scene's, and what a match is.
    const auto [rect, legend] =
        addTitledPanelWithLegendBelow(grid, 0, 2, 1, "each taxel, recorded against fitted", "taxel",
                                      "Kolmogorov-Smirnov distance");
    QVector<double> x, ks, match;
    for (const auto& t : fit.taxels) {
        x << t.taxel;
        ks << t.ks;
        match << t.ksMatch;
    }
    auto* limit = addSeries(rect, legend, "a match is at most", x, match, Qt::gray);
    limit->setLineStyle(QCPGraph::lsStepCenter);
    limit->setScatterStyle(QCPScatterStyle::ssNone);
    limit->setPen(QPen(Qt::gray, 1, Qt::DashLine));
    addSeries(rect, legend, "recorded against fitted", x, ks, seriesColour(0), false);
    rect->axis(QCPAxis::atBottom)->setRange(-0.6, double(fit.taxels.size()) - 0.4);
    integerTicks(rect->axis(QCPAxis::atBottom), fit.taxels.size() > 12 ? 4.0 : 1.0);
    rect->axis(QCPAxis::atLeft)->rescale();
    rect->axis(QCPAxis::atLeft)->setRangeLower(0);
    rect->axis(QCPAxis::atLeft)->setRangeUpper(rect->axis(QCPAxis::atLeft)->range().upper * 1.15);
    return true;
}

}  // namespace activetouch
