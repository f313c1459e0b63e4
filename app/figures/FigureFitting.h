#pragma once
// What a layout fits to the size a figure is drawn at, besides its panels' arrangement
// (FigureReflow.h): titles, captions and axis labels wrapped, tick labels thinned; and
// fitToLayout (FigureExport.h), which runs every fit.
#include <QFont>
#include <QSizeF>
#include <QString>

class QCPAbstractPlottable;
class QCPItemText;

namespace activetouch {

/// `text` broken into lines at spaces so that none is wider than `room` pixels in `font` (a word
/// wider than the room keeps its own line).
QString wrapped(const QString& text, const QFont& font, double room);

/// The size of a text item's text in its font, on its lines (its padding not included).
QSizeF textSize(const QCPItemText& label);

/// A plottable's name as the figure's code gave it: a legend inside a narrow panel shows it
/// wrapped over lines.
QString seriesName(const QCPAbstractPlottable* plottable);

/// An axis property (QStringList) naming the category at each integer coordinate, for an axis
/// whose tick labels name only some of them (Figure 5's orientations beyond twelve): what the
/// cursor read-out says there.
inline constexpr char kCategoryNames[] = "categoryNames";

}  // namespace activetouch
