#pragma once
// Outcome rates over many seeds (one seed = one whole run): each seed's outcome, and the rates
// over the seeds run so far with their 95 % intervals, so a reader sees how much a claim rests on.
#include <QString>
#include <QStringList>

#include "app/figures/FigureExport.h"

class QCustomPlot;

namespace activetouch {

struct SeedRates;

/// Left (above if `stacked`): per seed, the share of its active trials completed and of its
/// passive trials lost. Right (below): the running rates (active completed, passive lost,
/// recognised by both rules, runs with the paper's result whole) against the number of seeds, each
/// with its Wilson 95 % band. Stacked suits a panel taller than wide. False if there are no seeds.
bool buildSeedRatesFigure(QCustomPlot& plot, const SeedRates& rates, const QString& experiment,
                          bool stacked = false);

/// The size seed_rates is written at: wide, the two panels side by side.
inline constexpr FigureSize kSeedFigureSize =
    FigureSize::physical(kDoubleColumn_mm, 85, kFigureDpi);

/// Writes <outDir>/figures/seed_rates.{png,pdf,svg} at kSeedFigureSize, and where the runs measured
/// accuracy-versus-time sweeps, sweeps_perception.*, sweeps_following_pareto.* and
/// sweeps_robustness.*; returns the
/// files. Throws std::runtime_error naming what could not be written.
QStringList writeSeedFigures(const SeedRates& rates, const QString& experiment,
                             const QString& outDir);

}  // namespace activetouch
