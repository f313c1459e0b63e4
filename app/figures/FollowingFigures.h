#pragma once
// The paper's Figures 7 and 8 (traced paths: the object's outline, taps as dots, moves as lines,
// equal aspect, one colour per trial) and Figure 9 (path histograms beside the templates, with
// every match distance).
#include <QString>
#include <QStringList>
#include <vector>

#include "app/figures/FigureExport.h"
#include "core/control/FollowingSettings.h"

class QCustomPlot;

namespace activetouch {

struct RunResult;

/// Paths of the trials in `mode`, one panel per shape, under `title` and what the classifier the
/// trials followed with adds to it (classifierTitleNote). Returns false if there are none.
bool buildPathFigure(QCustomPlot& plot, const RunResult& result, FollowingMode mode,
                     const QString& title);

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

/// Writes each of runFigures() the run has as PNG, PDF and SVG into <outDir>/figures. Needs a
/// QApplication. Returns the files written.
QStringList writeRunFigures(const RunResult& result, const QString& outDir);

/// Figure 9: per recognised shape, its template and each trial's path histogram (paper's raw
/// rule), and the distances from each trial to every template. Returns false if nothing was
/// recognised.
bool buildRecognitionFigure(QCustomPlot& plot, const RunResult& result);

}  // namespace activetouch
