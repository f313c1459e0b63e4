#pragma once
// The paper's Figures 7 and 8 (traced paths: the object's outline, taps as dots, moves as lines,
// equal aspect, one colour per trial) and Figure 9 (path histograms beside the templates, with
// every match distance).
#include <QColor>
#include <QString>
#include <QStringList>
#include <algorithm>
#include <vector>

#include "app/figures/FigureExport.h"
#include "core/control/FollowingSettings.h"
#include "core/geometry/Vec2.h"

class QCustomPlot;
class QCPAxisRect;
class QCPCurve;
class QCPLegend;

namespace activetouch {

struct RunResult;
struct TrialRun;
class Polygon;

/// Paths of the trials in `mode`, one panel per shape, under `title` and what the classifier the
/// trials followed with adds to it (classifierTitleNote). Returns false if there are none.
bool buildPathFigure(QCustomPlot& plot, const RunResult& result, FollowingMode mode,
                     const QString& title);

/// Where the paths of a panel reach: the panel's ranges are fitted to it.
struct PathBox {
    Vec2 lo{1e9, 1e9}, hi{-1e9, -1e9};
    void add(Vec2 v) {
        lo = {std::min(lo.x, v.x), std::min(lo.y, v.y)};
        hi = {std::max(hi.x, v.x), std::max(hi.y, v.y)};
    }
};

/// Axis labels in mm, `title` on top and a legend inside the top right corner, which it returns.
QCPLegend* addPathPanel(QCPAxisRect* rect, const QString& title);
/// The object's outline in black, named "object".
QCPCurve* addOutline(QCPAxisRect* rect, QCPLegend* legend, const Polygon& outline, PathBox& box);
/// A trial's path: its moves as lines, its taps as dots of `dotSize`, in `colour`, named `name`.
/// For a trial that did not complete, also a cross where it ended, returned (not yet in the
/// legend); nullptr otherwise.
QCPCurve* addTrialPath(QCPAxisRect* rect, QCPLegend* legend, const TrialRun& t, QColor colour,
                       double dotSize, const QString& name, PathBox& box);
/// Lists `firstEnd` (if any) in the legend, marks the `furthest` contour points trials that did
/// not complete reached, and fits the panel to `box` at equal aspect, with `legendRoom` of the
/// box's height above it for a legend inside the panel.
void finishPathPanel(QCPAxisRect* rect, QCPLegend* legend, QCPCurve* firstEnd,
                     const std::vector<Vec2>& furthest, const PathBox& box,
                     double legendRoom = 0.35);

/// One figure a run writes: its file name (without extension), how it is drawn (false: the run
/// has nothing for it) and the size it is written at.
struct RunFigure {
    const char* file;
    bool (*build)(QCustomPlot& plot, const RunResult& result);
    FigureSize size;
};

/// Every figure a run can write, in order: 5, 6, 7-9 and the accuracy-versus-time sweeps. A
/// cancelled run, or one without a validation, draws only Figure 5.
const std::vector<RunFigure>& runFigures();

/// Writes each of runFigures() the run has as PNG, PDF and SVG into <outDir>/figures: at its
/// usual size, or `widthMm` wide (> 0) at its own height there (figureSizeFor). Needs a
/// QApplication. Returns the files written.
QStringList writeRunFigures(const RunResult& result, const QString& outDir, double widthMm = 0.0);

/// Figure 9: per recognised shape, its template and each trial's path histogram (paper's raw
/// rule), and the distances from each trial to every template. Returns false if nothing was
/// recognised.
bool buildRecognitionFigure(QCustomPlot& plot, const RunResult& result);

}  // namespace activetouch
