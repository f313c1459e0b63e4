#pragma once
// A figure's laid-out items as a reader sees them, read by painting the plot onto a recording
// device: every text drawn (with its box and size), every line segment, point and filled area the
// data draws, and every legend's box. The check on them names the figure, the size and the two
// items that collide: two texts overlapping, a text or a legend over plotted data, a text off the
// page, a journal figure's text outside 7-9 pt.
#include <QLineF>
#include <QPolygonF>
#include <QRectF>
#include <QString>
#include <QStringList>
#include <QVector>

class QCustomPlot;

namespace activetouch::test {

struct AuditText {
    QString text;
    QRectF box;     ///< the ink's bounding box, in the plot's pixels
    double points;  ///< the font's size in points (at the plot's logical resolution)
    bool inLegend;  ///< part of a legend (checked against the legend's box, not the data)
    bool cut = false;  ///< partly outside the area it is clipped to (its panel): cut off
};

struct FigureItems {
    QRectF page;
    QVector<AuditText> texts;
    QVector<QLineF> segments;  ///< what the data draws as lines (clipped to its panel)
    QVector<QPointF> marks;    ///< centres of the data's dots and markers
    QVector<QPolygonF> areas;  ///< the data's filled areas (bars, bands)
    QVector<QRectF> legends;   ///< boxes of legends drawn inside panels
    QVector<QRectF> panels;    ///< the panels' data rects
    bool layoutMoved = false;  ///< reading it moved a panel (then nothing read can be trusted)
};

/// Reads the items of `plot` as laid out now (call after layOutAt or a replot at its size).
FigureItems readFigureItems(QCustomPlot& plot);

/// What is wrong with the figure `name`: each line names the two items that collide or the one
/// out of bounds. With `journal`, every text must also be 7-9 pt.
QStringList auditFigure(const FigureItems& items, const QString& name, bool journal);

}  // namespace activetouch::test
