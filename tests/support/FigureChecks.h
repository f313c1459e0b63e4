#pragma once
// Checks of a figure's layout as a reader sees it, shared by the window's tests and the exported
// figures' tests: legends hide no data, titles and labels fit their panels, tick labels never
// overlap. Call after the plot has been laid out at its size (a replot).
#include <QFontMetricsF>
#include <QMap>
#include <QPair>
#include <QtTest>
#include <algorithm>
#include <cmath>

#include "qcustomplot.h"
#include "support/BoxText.h"

namespace activetouch::test {

/// Every equal-aspect panel of `plot`: one unit per pixel on both axes, the ranges asked for
/// inside the view, one of them exactly; its ranges into `views` by panel index.
inline void checkEqualAspect(QCustomPlot& plot, const QString& name,
                             QMap<int, QPair<QCPRange, QCPRange>>& views) {
    const QList<QCPAxisRect*> rects = plot.axisRects();
    for (int i = 0; i < rects.size(); ++i) {
        QCPAxisRect* rect = rects[i];
        const QVariant wantX = rect->property("equalAspectX");
        if (!wantX.isValid()) continue;
        const QString what = QString("%1 panel %2").arg(name).arg(i);
        QVERIFY2(rect->width() > 20 && rect->height() > 20, qPrintable(what));
        // The y range asked for, with the room a legend over the data took (if it took any).
        const QVariant shownY = rect->property("equalAspectShownY");
        const QPointF wx = wantX.toPointF(),
                      wy = (shownY.isValid() ? shownY : rect->property("equalAspectY")).toPointF();
        const QCPRange x = rect->axis(QCPAxis::atBottom)->range();
        const QCPRange y = rect->axis(QCPAxis::atLeft)->range();
        const double ratio = (x.size() / rect->width()) / (y.size() / rect->height());
        QVERIFY2(std::abs(ratio - 1.0) < 0.02,
                 qPrintable(what + QString(": x/y scale %1").arg(ratio)));
        QVERIFY2(x.lower <= wx.x() + 1e-9 && x.upper >= wx.y() - 1e-9, qPrintable(what));
        QVERIFY2(y.lower <= wy.x() + 1e-9 && y.upper >= wy.y() - 1e-9, qPrintable(what));
        QVERIFY2(std::abs(x.size() - (wx.y() - wx.x())) < 1e-6 ||
                     std::abs(y.size() - (wy.y() - wy.x())) < 1e-6,
                 qPrintable(what + ": both axes widened"));
        views[i] = {x, y};
    }
}

/// No legend drawn inside a panel of `plot` covers a data point or a bar of that panel: a
/// reader must see every value, the tallest bars and the paths' extremes above all.
inline void checkLegendsClearOfData(QCustomPlot& plot, const QString& name) {
    for (QCPAxisRect* rect : plot.axisRects()) {
        QList<QRectF> legends;
        for (QCPLayoutElement* e : rect->insetLayout()->elements(false))
            if (auto* legend = qobject_cast<QCPLegend*>(e); legend && legend->itemCount() > 0)
                legends << QRectF(legend->outerRect());
        if (legends.isEmpty()) continue;
        const QString what = QString("%1 panel %2").arg(name, rect->axis(QCPAxis::atTop)->label());
        for (QCPAbstractPlottable* p : rect->plottables()) {
            QList<QPointF> points;
            if (auto* graph = qobject_cast<QCPGraph*>(p)) {
                for (const auto& d : *graph->data())
                    points << graph->coordsToPixels(d.key, d.value);
            } else if (auto* curve = qobject_cast<QCPCurve*>(p)) {
                for (const auto& d : *curve->data())
                    points << curve->coordsToPixels(d.key, d.value);
            } else if (auto* bars = qobject_cast<QCPBars*>(p)) {
                // A bar is an area: probe the legend's own pixels for it.
                for (const QRectF& legend : legends)
                    for (double x = legend.left(); x <= legend.right(); x += 2)
                        for (double y = legend.top(); y <= legend.bottom(); y += 2)
                            if (bars->selectTest(QPointF(x, y), false) >= 0)
                                points << QPointF(x, y);
            }
            for (const QPointF& pt : points) {
                // A missing value (NaN, e.g. no completed trial) is a gap, drawn nowhere.
                if (!std::isfinite(pt.x()) || !std::isfinite(pt.y())) continue;
                for (const QRectF& legend : legends)
                    QVERIFY2(!legend.contains(pt),
                             qPrintable(what + QString(": the legend covers %1 at (%2, %3)")
                                                   .arg(p->name())
                                                   .arg(pt.x())
                                                   .arg(pt.y())));
            }
        }
    }
}

// Every legend entry is drawn whole inside the figure: a legend under a panel wider than the
// figure has its last entries cut off at the figure's edge.
inline void checkLegendsFitTheFigure(QCustomPlot& plot, const QString& name) {
    QList<QCPLegend*> legends;
    for (QCPLayoutElement* e : plot.plotLayout()->elements(true))
        if (auto* legend = qobject_cast<QCPLegend*>(e)) legends << legend;
    for (QCPAxisRect* rect : plot.axisRects())
        for (QCPLayoutElement* e : rect->insetLayout()->elements(false))
            if (auto* legend = qobject_cast<QCPLegend*>(e)) legends << legend;
    const QRect figure = plot.viewport();
    for (QCPLegend* legend : legends) {
        if (!legend->visible()) continue;
        for (int i = 0; i < legend->itemCount(); ++i) {
            QCPAbstractLegendItem* item = legend->item(i);
            if (!item) continue;
            const QRect box = item->outerRect();
            const int needed = item->minimumOuterSizeHint().width();
            QVERIFY2(box.left() >= figure.left() - 1 && box.right() <= figure.right() + 1 &&
                         box.width() >= needed - 1,
                     qPrintable(QString("%1: the legend entry %2 spans x %3..%4 (needs %5 px) in a "
                                        "figure of x %6..%7")
                                    .arg(name)
                                    .arg(i)
                                    .arg(box.left())
                                    .arg(box.right())
                                    .arg(needed)
                                    .arg(figure.left())
                                    .arg(figure.right())));
        }
    }
}

// Every panel's title fits over its own panel and its y-axis label beside it: wider, a title runs
// into the next panel's title or the colour scale beside it, and a label is cut off. Legends fit
// the figure.
inline void checkLabelsFitTheirPanels(QCustomPlot& plot, const QString& name) {
    checkLegendsFitTheFigure(plot, name);
    if (QTest::currentTestFailed()) return;
    // A figure's and a row's titles fit the figure's width.
    for (QCPLayoutElement* e : plot.plotLayout()->elements(true)) {
        auto* title = qobject_cast<QCPTextElement*>(e);
        if (!title || !title->visible()) continue;
        const double width =
            QFontMetricsF(title->font()).boundingRect(QRectF(), 0, title->text()).width();
        QVERIFY2(width <= plot.width(),
                 qPrintable(QString("%1: the title '%2' is %3 px wide over a figure of %4 px")
                                .arg(name, title->text())
                                .arg(width, 0, 'f', 0)
                                .arg(plot.width())));
    }
    // Text placed at a point (a threshold, a setting) is not cut off by its panel's edge.
    for (int i = 0; i < plot.itemCount(); ++i) {
        auto* text = qobject_cast<QCPItemText*>(plot.item(i));
        if (!text || !text->visible() || !text->clipToAxisRect() || !text->clipAxisRect()) continue;
        const QPointF at = text->position->pixelPosition();
        // The text with its padding is aligned at the point; the text sits inside the padding.
        const QMargins pad = text->padding();
        const QSizeF size = QFontMetricsF(text->font())
                                .boundingRect(QRectF(), Qt::TextDontClip, text->text())
                                .size()
                                .grownBy(pad);
        const Qt::Alignment a = text->positionAlignment();
        const double left = a & Qt::AlignRight     ? at.x() - size.width()
                            : a & Qt::AlignHCenter ? at.x() - size.width() / 2
                                                   : at.x();
        const double top = a & Qt::AlignBottom    ? at.y() - size.height()
                           : a & Qt::AlignVCenter ? at.y() - size.height() / 2
                                                  : at.y();
        const QRectF box = QRectF(left, top, size.width(), size.height()).marginsRemoved(pad);
        const QRectF panel = QRectF(text->clipAxisRect()->rect()).adjusted(-1, -1, 1, 1);
        QVERIFY2(panel.contains(box),
                 qPrintable(QString("%1 panel %2: the label '%3' at %4 is cut off by the "
                                    "panel's edge %5")
                                .arg(name, text->clipAxisRect()->axis(QCPAxis::atTop)->label(),
                                     text->text(), boxText(box), boxText(panel))));
    }
    auto extent = [](const QCPAxis* axis) {
        return QFontMetricsF(axis->labelFont())
            .boundingRect(QRectF(), Qt::TextDontClip, axis->label())
            .width();
    };
    for (QCPAxisRect* rect : plot.axisRects()) {
        const QRect outer = rect->outerRect();
        const QCPAxis* top = rect->axis(QCPAxis::atTop);
        if (top->visible() && !top->label().isEmpty()) {
            const double width = extent(top), centre = rect->rect().center().x();
            QVERIFY2(
                centre - width / 2 >= outer.left() - 1 && centre + width / 2 <= outer.right() + 1,
                qPrintable(QString("%1 panel %2: the title is %3 px wide over a panel of %4 px")
                               .arg(name, top->label())
                               .arg(width, 0, 'f', 0)
                               .arg(outer.width())));
        }
        // Tick labels never run into each other: the ticker spaces ticks by value, not by the
        // width of their labels, and named ticks (shapes, orientations) are never thinned out.
        for (QCPAxis* axis : rect->axes()) {
            if (!axis->visible() || !axis->tickLabels()) continue;
            const QFontMetricsF metrics(axis->tickLabelFont());
            const bool across = axis->orientation() == Qt::Horizontal;
            const QVector<double> ticks = axis->tickVector();
            const QVector<QString> labels = axis->tickVectorLabels();
            QList<QPair<double, double>> spans;  // pixel extent of each visible label
            for (int t = 0; t < ticks.size() && t < labels.size(); ++t) {
                if (!axis->range().contains(ticks[t]) || labels[t].isEmpty()) continue;
                const QRectF box = metrics.boundingRect(QRectF(), Qt::TextDontClip, labels[t]);
                const double centre = axis->coordToPixel(ticks[t]);
                const double half = 0.5 * (across ? box.width() : box.height());
                spans << qMakePair(centre - half, centre + half);
            }
            std::sort(spans.begin(), spans.end());
            for (int t = 1; t < spans.size(); ++t)
                QVERIFY2(spans[t].first >= spans[t - 1].second,
                         qPrintable(QString("%1 panel %2: tick labels overlap by %3 px on the "
                                            "%4 axis (%5)")
                                        .arg(name, top->label())
                                        .arg(spans[t - 1].second - spans[t].first, 0, 'f', 0)
                                        .arg(across ? "x" : "y", labels.toList().join(" "))));
        }
        const QCPAxis* left = rect->axis(QCPAxis::atLeft);
        if (left->visible() && !left->label().isEmpty()) {
            const double length = extent(left), centre = rect->rect().center().y();
            QVERIFY2(
                centre - length / 2 >= outer.top() - 1 && centre + length / 2 <= outer.bottom() + 1,
                qPrintable(QString("%1 panel %2: the y label '%3' is %4 px long beside a "
                                   "panel of %5 px")
                               .arg(name, top->label(), left->label())
                               .arg(length, 0, 'f', 0)
                               .arg(outer.height())));
        }
    }
}

}  // namespace activetouch::test
