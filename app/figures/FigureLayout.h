#pragma once
// The layout every figure shares: one column of rows, row 0 the title, each further row a grid of
// panels; panels titled on their top axis.
#include <QColor>
#include <QString>
#include <QVector>
#include <vector>

#include "core/geometry/Vec2.h"

class QCustomPlot;
class QCPAxisRect;
class QCPLayoutGrid;
class QCPCurve;
class QCPAxis;
class QCPGraph;
class QCPLegend;
class QCPColorGradient;

namespace activetouch {

/// Empties `plot` and puts `title` in row 0, and under the figure's rows a `caption` (if any):
/// what the figure measured, as a caption gives it (lines broken with \n). Each panel fills its
/// own legend.
void startFigure(QCustomPlot& plot, const QString& title, const QString& caption = {});

/// Appends a row holding a grid for panels; `stretch` weighs its height against the other rows.
QCPLayoutGrid* addFigureRow(QCustomPlot& plot, double stretch);

/// A curve through `points` (closed back to the first if `closed`) on the given axes.
QCPCurve* addPolyline(QCPAxis* x, QCPAxis* y, const std::vector<Vec2>& points, bool closed);

/// Writes `text` as the panel's title on its top axis.
void setPanelTitle(QCPAxisRect* rect, const QString& text);

/// The heatmaps' colour gradient: thermal from black, ending in yellow rather than white, so that
/// a cell at or above the top of a fixed scale never looks like the white background.
QCPColorGradient heatGradient();

/// The colour of the i-th series in a panel (a palette of 8, repeating).
QColor seriesColour(int i);

/// Taxel k's colour, the same in the window's views and every figure: twelve colours that stay
/// distinct in print and for the common colour-vision deficiencies.
QColor taxelColour(int k);

/// Adds a panel at `column` of `grid`'s first row, titled, with axis labels.
QCPAxisRect* addTitledPanel(QCPLayoutGrid* grid, int column, const QString& title,
                            const QString& xLabel, const QString& yLabel);

/// Ticks every `step` on `axis`, never rescaled: for counted things (positions, taxels, seeds).
void integerTicks(QCPAxis* axis, double step);

/// A legend inside the panel's top right corner.
QCPLegend* addLegend(QCPAxisRect* rect);

/// A panel with its legend in a row of its own under it, at most `perLine` entries to a line (0:
/// all on one line), fewer where the figure is too narrow for them (fitLegendLines): for panels
/// whose data may fill any corner, where an inside legend would hide some.
struct PanelWithLegend {
    QCPAxisRect* rect;
    QCPLegend* legend;
};
PanelWithLegend addPanelWithLegendBelow(QCPLayoutGrid* grid, int row, int column, int perLine);
/// The same, titled, with axis labels.
PanelWithLegend addTitledPanelWithLegendBelow(QCPLayoutGrid* grid, int row, int column, int perLine,
                                              const QString& title, const QString& xLabel,
                                              const QString& yLabel);

/// A legend in a figure row of its own (under the panels), at most `perLine` entries to a line,
/// fewer where the figure is too narrow for them (fitLegendLines).
QCPLegend* addLegendRow(QCustomPlot& plot, int perLine);

/// Puts as many entries on each line of every legend made by addPanelWithLegendBelow as its share
/// of the figure's width holds, up to the number asked for, and at least one. Returns whether any
/// legend changed; does not replot. Call after a layout.
bool fitLegendLines(QCustomPlot& plot);

/// A graph of (x, y) in the panel: points joined by lines unless `lines` is false; listed in
/// `legend` if one is given.
QCPGraph* addSeries(QCPAxisRect* rect, QCPLegend* legend, const QString& name,
                    const QVector<double>& x, const QVector<double>& y, QColor colour,
                    bool lines = true);

/// A quantity tracked as seeds accumulate: after each seed, its value and its 95 % interval.
struct RunningValue {
    QVector<double> x, value, low, high;
    void append(double at, double v, double lo, double hi) {
        x << at;
        value << v;
        low << lo;
        high << hi;
    }
};

/// `r` as a line with its interval as a shaded band (the band's edges stay out of `legend`);
/// markers on the line only while there are few points. Nothing if `r` is empty.
void addRunningBand(QCPAxisRect* rect, QCPLegend* legend, const QString& name,
                    const RunningValue& r, QColor colour);

}  // namespace activetouch
