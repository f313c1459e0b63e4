#include <QLineF>
#include <QMap>
#include <algorithm>
#include <cmath>
#include <vector>

#include "app/figures/FigureFitting.h"
#include "app/figures/FigureReflow.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {
/// Room between a label and its point, pixels.
constexpr int kGap_px = 4;

/// What a label must not cover in a panel: the data's points and line segments and the labels
/// placed before it, in pixels.
struct Obstacles {
    std::vector<QPointF> points;
    std::vector<QLineF> lines;
    std::vector<QRectF> labels;

    bool hit(const QRectF& box) const {
        for (const QRectF& placed : labels)
            if (box.intersects(placed)) return true;
        for (const QPointF& p : points)
            if (box.adjusted(-2, -2, 2, 2).contains(p)) return true;
        for (const QLineF& l : lines) {
            if (box.contains(l.p1()) || box.contains(l.p2())) return true;
            const QLineF edges[4] = {{box.topLeft(), box.topRight()},
                                     {box.topRight(), box.bottomRight()},
                                     {box.bottomRight(), box.bottomLeft()},
                                     {box.bottomLeft(), box.topLeft()}};
            for (const QLineF& e : edges)
                if (l.intersects(e, nullptr) == QLineF::BoundedIntersection) return true;
        }
        return false;
    }
};

bool finite(const QPointF& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y());
}

void addGraph(const QCPGraph* g, Obstacles& o) {
    const bool lines = g->lineStyle() != QCPGraph::lsNone && g->pen().style() != Qt::NoPen;
    QPointF last(qQNaN(), qQNaN());
    for (const auto& d : *g->data()) {
        const QPointF p = g->coordsToPixels(d.key, d.value);
        if (finite(p)) {
            if (g->scatterStyle().shape() != QCPScatterStyle::ssNone) o.points.push_back(p);
            if (lines && finite(last)) o.lines.emplace_back(last, p);
        }
        last = p;
    }
}

void addErrorBars(const QCPErrorBars* bars, Obstacles& o) {
    const auto* graph = qobject_cast<const QCPGraph*>(bars->dataPlottable());
    if (!graph) return;
    const int n = std::min<int>(graph->data()->size(), bars->data()->size());
    for (int i = 0; i < n; ++i) {
        const double key = graph->data()->at(i)->key, value = graph->data()->at(i)->value;
        const QCPErrorBarsData& e = bars->data()->at(i);
        const bool alongValue = bars->errorType() == QCPErrorBars::etValueError;
        const QPointF low = alongValue ? graph->coordsToPixels(key, value - e.errorMinus)
                                       : graph->coordsToPixels(key - e.errorMinus, value);
        const QPointF high = alongValue ? graph->coordsToPixels(key, value + e.errorPlus)
                                        : graph->coordsToPixels(key + e.errorPlus, value);
        if (finite(low) && finite(high)) o.lines.emplace_back(low, high);
    }
}

Obstacles obstaclesIn(const QCPAxisRect* rect) {
    Obstacles o;
    for (QCPAbstractPlottable* p : rect->plottables()) {
        if (!p->visible()) continue;
        if (auto* g = qobject_cast<QCPGraph*>(p)) addGraph(g, o);
        if (auto* bars = qobject_cast<QCPErrorBars*>(p)) addErrorBars(bars, o);
        if (auto* curve = qobject_cast<QCPCurve*>(p)) {
            QPointF last(qQNaN(), qQNaN());
            for (const auto& d : *curve->data()) {
                const QPointF q = curve->coordsToPixels(d.key, d.value);
                if (finite(q)) o.points.push_back(q);
                if (finite(q) && finite(last)) o.lines.emplace_back(last, q);
                last = q;
            }
        }
    }
    return o;
}

/// The sides a label is tried on, in order.
const Qt::Alignment kSides[] = {
    Qt::AlignLeft | Qt::AlignVCenter,   Qt::AlignRight | Qt::AlignVCenter,
    Qt::AlignHCenter | Qt::AlignBottom, Qt::AlignHCenter | Qt::AlignTop,
    Qt::AlignLeft | Qt::AlignBottom,    Qt::AlignRight | Qt::AlignBottom,
    Qt::AlignLeft | Qt::AlignTop,       Qt::AlignRight | Qt::AlignTop};

/// The box a label aligned `side` at `at` takes, with its gap.
QRectF boxAt(const QPointF& at, const QSizeF& size, Qt::Alignment side) {
    const double w = size.width() + 2 * kGap_px, h = size.height() + 2 * kGap_px;
    const double left = side & Qt::AlignRight     ? at.x() - w
                        : side & Qt::AlignHCenter ? at.x() - w / 2
                                                  : at.x();
    const double top = side & Qt::AlignBottom    ? at.y() - h
                       : side & Qt::AlignVCenter ? at.y() - h / 2
                                                 : at.y();
    return QRectF(left, top, w, h);
}
}  // namespace

void markPointLabel(QCPItemText* label) {
    label->setProperty("namesPoint", true);
    label->setVisible(false);  // until a layout finds it a side (placePointLabels)
    label->setPadding(QMargins(kGap_px, kGap_px, kGap_px, kGap_px));
}

bool placePointLabels(QCustomPlot& plot) {
    QMap<QCPAxisRect*, std::vector<QCPItemText*>> byPanel;
    for (int i = 0; i < plot.itemCount(); ++i)
        if (auto* label = qobject_cast<QCPItemText*>(plot.item(i));
            label && label->property("namesPoint").toBool() && label->clipAxisRect())
            byPanel[label->clipAxisRect()].push_back(label);
    bool changed = false;
    for (auto it = byPanel.begin(); it != byPanel.end(); ++it) {
        const QRectF panel = QRectF(it.key()->rect());
        Obstacles o = obstaclesIn(it.key());
        for (QCPItemText* label : it.value()) {
            const QPointF at = label->position->pixelPosition();
            const QSizeF size = textSize(*label);
            const Qt::Alignment was = label->positionAlignment();
            const bool wasShown = label->visible();
            bool placed = false;
            for (Qt::Alignment side : kSides) {
                const QRectF box = boxAt(at, size, side);
                if (!panel.contains(box) || o.hit(box)) continue;
                label->setPositionAlignment(side);
                label->setVisible(true);
                o.labels.push_back(box);  // what later labels must not cover
                placed = true;
                break;
            }
            if (!placed) label->setVisible(false);
            changed = changed || label->positionAlignment() != was || label->visible() != wasShown;
        }
    }
    return changed;
}

}  // namespace activetouch
