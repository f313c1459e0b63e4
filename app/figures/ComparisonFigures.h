#pragma once
// Two experiments compared trial by trial on the same seeds (core/analysis/PairedComparison.h): for
// each part of the paper's result, B's rate minus A's with its 95 % interval, McNemar's p beside
// it, and what each costs in robot time per run.
#include <QString>
#include <QStringList>

#include "app/figures/FigureExport.h"

class QCustomPlot;

namespace activetouch {

struct PairedComparison;
struct TrialPairRun;

/// Left (above if `stacked`): one row per outcome compared (active trials completed, passive
/// trials lost at a corner, completed paths recognised by the paper's rule, runs with the paper's
/// result whole): the difference B - A in percentage points as a point with its interval, a line
/// at no difference, and under each part's name its counts and McNemar's p. Right (below): each
/// difference with its interval after each seed (PairedComparison::soFar), so a reader sees how it
/// settles, its value axis fitted to the seeds from a tenth of them on. False (with the title
/// only) if nothing was compared.
bool buildComparisonFigure(QCustomPlot& plot, const PairedComparison& comparison,
                           bool stacked = false);

/// One trial of one seed as A and B ran it (runTrialPair): the object, both paths with their taps,
/// where a trial that did not complete ended and how far along the contour it got; each path's
/// legend entry says how it ended and the shape the paper's rule named it.
bool buildTrialPairFigure(QCustomPlot& plot, const TrialPairRun& pair);

/// The size compare is written at: wide, the two panels side by side.
inline constexpr FigureSize kComparisonFigureSize =
    FigureSize::physical(kDoubleColumn_mm, 70, kFigureDpi);

/// The size a trial pair is written at: one panel, its legend under it.
inline constexpr FigureSize kTrialPairFigureSize =
    FigureSize::physical(kDoubleColumn_mm * 0.75, 125, kFigureDpi);

/// Writes <outDir>/figures/<trialPairFileStem>.{png,pdf,svg}; returns the files. Throws
/// std::runtime_error naming what could not be written.
QStringList writeTrialPairFigures(const TrialPairRun& pair, const QString& outDir);

/// Writes <outDir>/figures/compare.{png,pdf,svg}; returns the files (none if nothing was
/// compared). Throws std::runtime_error naming what could not be written.
QStringList writeComparisonFigures(const PairedComparison& comparison, const QString& outDir);

}  // namespace activetouch
