#pragma once
// The layout every figure shares: one column of rows, row 0 the title, each further row a grid of
// panels; panels titled on their top axis.
#include <QString>

class QCustomPlot;
class QCPAxisRect;
class QCPLayoutGrid;

namespace activetouch {

/// Empties `plot` and puts `title` in row 0. Each panel fills its own legend.
void startFigure(QCustomPlot& plot, const QString& title);

/// Appends a row holding a grid for panels; `stretch` weighs its height against the other rows.
QCPLayoutGrid* addFigureRow(QCustomPlot& plot, double stretch);

/// Writes `text` as the panel's title on its top axis.
void setPanelTitle(QCPAxisRect* rect, const QString& text);

}  // namespace activetouch
