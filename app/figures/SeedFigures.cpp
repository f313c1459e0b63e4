#include "app/figures/SeedFigures.h"

#include <stdexcept>

#include "app/figures/FigureExport.h"
#include "app/figures/FigureLayout.h"
#include "app/figures/SweepFigures.h"
#include "core/analysis/SeedRates.h"
#include "core/analysis/SweepRates.h"
#include "qcustomplot.h"

namespace activetouch {
namespace {

/// A running rate: its value and 95 % band after each seed, in percent.
RunningValue running(const SeedRates& all, Rate (*part)(const SeedOutcome&)) {
    RunningValue r;
    stats::ClusteredProportion pooled;
    int runs = 0;
    for (const SeedOutcome& s : all.seeds) {
        const Rate p = part(s);
        ++runs;
        pooled.add(p.count, p.total);
        const Rate sofar = Rate::pooled(pooled);
        if (sofar.total == 0) continue;
        r.append(double(runs), 100.0 * sofar.fraction(), 100.0 * sofar.low(), 100.0 * sofar.high());
    }
    return r;
}

}  // namespace

bool buildSeedRatesFigure(QCustomPlot& plot, const SeedRates& rates, const QString& experiment,
                          bool stacked) {
    const int n = static_cast<int>(rates.seeds.size());
    const QString range =
        n == 0 ? QString()
               : QString("seeds %1-%2").arg(rates.seeds.front().seed).arg(rates.seeds.back().seed);
    startFigure(plot, QString("%1: rates over %2").arg(experiment, range));
    if (n == 0) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    QCPLayoutGrid* below = stacked ? addFigureRow(plot, 1.4) : grid;
    // A seed's share may be anything from 0 to 100 % and the bands may fill any corner: both
    // legends go under their panels.
    const auto [each, le] = addTitledPanelWithLegendBelow(grid, 0, 0, /*perLine=*/2, "each seed",
                                                          "seed", "share of the seed's trials (%)");
    const auto [sofar, ls] =
        addTitledPanelWithLegendBelow(below, 0, stacked ? 0 : 1, /*perLine=*/3,
                                      "rates so far, 95 % intervals", "seeds run", "rate (%)");
    if (!stacked) {
        grid->setColumnStretchFactor(0, 1.0);
        grid->setColumnStretchFactor(1, 1.4);
    }

    QVector<double> seed, completed, lost;
    QVector<double> passiveSeed;
    for (const SeedOutcome& s : rates.seeds) {
        if (s.activeTrials > 0) {
            seed << double(s.seed);
            completed << 100.0 * s.activeCompleted / s.activeTrials;
        }
        if (s.passiveTrials > 0) {
            passiveSeed << double(s.seed);
            lost << 100.0 * s.passiveLost / s.passiveTrials;
        }
    }
    if (!seed.isEmpty())
        addSeries(each, le, "active completed", seed, completed, seriesColour(0), false);
    if (!passiveSeed.isEmpty())
        addSeries(each, le, "passive lost", passiveSeed, lost, seriesColour(3), false)
            ->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCross, seriesColour(3), 7));
    const double first = double(rates.seeds.front().seed), last = double(rates.seeds.back().seed);
    // Seeds and counts of seeds are whole numbers: ticks at whole steps only.
    QSharedPointer<QCPAxisTickerFixed> whole(new QCPAxisTickerFixed);
    whole->setTickStep(1.0);
    whole->setScaleStrategy(QCPAxisTickerFixed::ssMultiples);
    each->axis(QCPAxis::atBottom)->setTicker(whole);
    sofar->axis(QCPAxis::atBottom)->setTicker(whole);
    each->axis(QCPAxis::atBottom)->setRange(first - 0.5, last + 0.5);
    each->axis(QCPAxis::atLeft)->setRange(-5.0, 105.0);

    addRunningBand(sofar, ls, "active completed", running(rates, activeCompletedIn),
                   seriesColour(0));
    addRunningBand(sofar, ls, "passive lost", running(rates, passiveLostIn), seriesColour(3));
    addRunningBand(sofar, ls, "recognised, paper's rule", running(rates, recognisedRawIn),
                   seriesColour(2));
    addRunningBand(sofar, ls, "recognised, smoothed", running(rates, recognisedSmoothedIn),
                   seriesColour(4));
    addRunningBand(sofar, ls, "runs with the paper's result whole", running(rates, paperResultIn),
                   seriesColour(7));
    sofar->axis(QCPAxis::atBottom)->setRange(0.5, n + 0.5);
    sofar->axis(QCPAxis::atLeft)->setRange(0.0, 102.0);
    return true;
}

QStringList writeSeedFigures(const SeedRates& rates, const QString& experiment,
                             const QString& outDir) {
    const QString dir = figuresDirectory(outDir);
    QStringList files;
    {
        QCustomPlot plot;
        if (buildSeedRatesFigure(plot, rates, experiment))
            files << exportFigure(plot, dir + "/seed_rates", {"png", "pdf", "svg"},
                                  kSeedFigureSize);
    }
    const SweepRates sweeps = sweepRates(rates.seeds);
    for (auto [build, name] : {std::pair{&buildPerceptionSweepOverSeedsFigure, "sweeps_perception"},
                               std::pair{&buildFollowingParetoFigure, "sweeps_following_pareto"},
                               std::pair{&buildRobustnessFigure, "sweeps_robustness"}}) {
        QCustomPlot plot;
        if (build(plot, sweeps))
            files << exportFigure(plot, dir + "/" + name, {"png", "pdf", "svg"},
                                  FigureSize::physical(kDoubleColumn_mm, 120, kFigureDpi));
    }
    return files;
}

}  // namespace activetouch
