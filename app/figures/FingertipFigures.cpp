#include "app/figures/FingertipFigures.h"

#include "app/figures/FigureLayout.h"
#include "qcustomplot.h"

namespace activetouch {

bool buildFingertipFigure(QCustomPlot& plot, const FingertipFigureData& data) {
    startFigure(plot, QString("The %1 fingertip at rest: real beside simulated").arg(data.finger),
                data.caption);
    const int taxels = static_cast<int>(data.sigma.size());
    if (taxels == 0) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    // Resting noise per taxel, with its interval over the recordings, and each scene's.
    const auto [noise, noiseLegend] = addTitledPanelWithLegendBelow(
        grid, 0, 0, 2, "resting noise", "taxel", "standard deviation (counts)");
    RunningValue real;
    double most = 0.0;
    for (int k = 0; k < taxels; ++k) {
        real.append(k, data.sigma[std::size_t(k)], data.sigmaLow[std::size_t(k)],
                    data.sigmaHigh[std::size_t(k)]);
        most = std::max(most, data.sigmaHigh[std::size_t(k)]);
    }
    addRunningBand(noise, noiseLegend, "real, with 95 % interval", real, seriesColour(0));
    for (std::size_t s = 0; s < data.scenes.size(); ++s) {
        const auto& scene = data.scenes[s];
        addSeries(noise, noiseLegend, scene.name, {-0.5, taxels - 0.5}, {scene.sigma, scene.sigma},
                  seriesColour(int(s) + 1));
        most = std::max(most, scene.sigma);
    }
    noise->axis(QCPAxis::atBottom)->setRange(-0.5, taxels - 0.5);
    integerTicks(noise->axis(QCPAxis::atBottom), taxels > 12 ? 3.0 : 1.0);
    noise->axis(QCPAxis::atLeft)->setRange(0.0, 1.1 * most);
    // Each taxel's resting readings against each scene's, by the Kolmogorov-Smirnov distance.
    const auto [ks, ksLegend] =
        addTitledPanelWithLegendBelow(grid, 0, 1, 2, "resting readings, real against simulated",
                                      "taxel", "Kolmogorov-Smirnov distance");
    double largest = 0.1;
    for (std::size_t s = 0; s < data.scenes.size(); ++s) {
        QVector<double> x, y;
        for (std::size_t k = 0; k < data.scenes[s].ks.size(); ++k) {
            x << double(k);
            y << data.scenes[s].ks[k];
            largest = std::max(largest, data.scenes[s].ks[k]);
        }
        addSeries(ks, ksLegend, data.scenes[s].name, x, y, seriesColour(int(s) + 1));
    }
    auto* line = addSeries(ks, ksLegend, "0.1", {-0.5, taxels - 0.5}, {0.1, 0.1}, Qt::gray);
    line->setScatterStyle(QCPScatterStyle::ssNone);
    line->setPen(QPen(Qt::gray, 1, Qt::DashLine));
    ks->axis(QCPAxis::atBottom)->setRange(-0.5, taxels - 0.5);
    integerTicks(ks->axis(QCPAxis::atBottom), taxels > 12 ? 3.0 : 1.0);
    ks->axis(QCPAxis::atLeft)->setRange(0.0, 1.1 * largest);
    return true;
}

}  // namespace activetouch
