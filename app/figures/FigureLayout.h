#pragma once
// The layout every figure shares: one column of rows, row 0 the title, each further row a grid of
// panels; panels titled on their top axis.
#include <QString>
#include <vector>

#include "core/geometry/Vec2.h"

class QCustomPlot;
class QCPAxisRect;
class QCPLayoutGrid;
class QCPCurve;
class QCPAxis;

namespace activetouch {

/// Empties `plot` and puts `title` in row 0. Each panel fills its own legend.
void startFigure(QCustomPlot& plot, const QString& title);

/// Appends a row holding a grid for panels; `stretch` weighs its height against the other rows.
QCPLayoutGrid* addFigureRow(QCustomPlot& plot, double stretch);

/// A curve through `points` (closed back to the first if `closed`) on the given axes.
QCPCurve* addPolyline(QCPAxis* x, QCPAxis* y, const std::vector<Vec2>& points, bool closed);

/// Writes `text` as the panel's title on its top axis.
void setPanelTitle(QCPAxisRect* rect, const QString& text);

}  // namespace activetouch
