#pragma once
// What the value label under the cursor says and where it goes: each value named by its axis
// (the quantity and unit read from the axis label, "pressure (counts)"), a category by its name
// rather than its index (orientation "left", shape "C"), numbers to four significant figures; the
// label kept whole inside the plot.
#include <QPair>
#include <QPointF>
#include <QRectF>
#include <QString>

#include "app/figures/FigureFitting.h"

class QCPAxis;

namespace activetouch {

/// "pressure (counts)" -> {"pressure", "counts"}; a label without a unit keeps it empty.
QPair<QString, QString> quantityOf(const QString& label);

/// `v` to four significant figures: 0.5, 3.142, 125, 1235, 12346 (an integer or a value of
/// 1000 or more keeps its whole units rather than an exponent), 1.235e-05.
QString readoutNumber(double v);

/// The category's name at `v` on `axis`, or empty where the axis is not one of categories:
/// its kCategoryNames, else a text ticker whose ticks are consecutive integers (within half a
/// step), else a text tick exactly at `v`. A tick label's first line.
QString categoryAt(const QCPAxis* axis, double v);

/// "name value unit" for a value on `axis` ("orientation left", "time in the tap 0.5 s").
QString axisValueText(const QCPAxis* axis, double v);

/// Where a label of `size` goes beside `cursor` so that it lies whole inside `plot` (8 px from
/// its edges where room allows): right of and above the cursor, else left, else below.
QRectF readoutPlace(const QRectF& plot, const QPointF& cursor, const QSizeF& size);

}  // namespace activetouch
