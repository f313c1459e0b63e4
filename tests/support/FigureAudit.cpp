#include "support/FigureAudit.h"

#include <QFontMetricsF>
#include <QPaintDevice>
#include <QPaintEngine>
#include <QPainterPath>
#include <QTextItem>
#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>

#include "qcustomplot.h"
#include "support/BoxText.h"

namespace activetouch::test {
namespace {

/// The part of `line` inside `clip` (Liang-Barsky), if any.
std::optional<QLineF> clipped(const QLineF& line, const QRectF& clip) {
    const double dx = line.dx(), dy = line.dy();
    double t0 = 0.0, t1 = 1.0;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {line.x1() - clip.left(), clip.right() - line.x1(), line.y1() - clip.top(),
                         clip.bottom() - line.y1()};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0) return std::nullopt;
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0.0)
            t0 = std::max(t0, t);
        else
            t1 = std::min(t1, t);
        if (t0 > t1) return std::nullopt;
    }
    return QLineF(line.pointAt(t0), line.pointAt(t1));
}

/// Records what is painted on it, in device pixels, clipped as the painter clips.
class RecordingEngine : public QPaintEngine {
public:
    RecordingEngine(FigureItems& items, bool texts, bool data, const QList<QRectF>& backgrounds)
        : QPaintEngine(QPaintEngine::AllFeatures),
          items_(items),
          texts_(texts),
          data_(data),
          backgrounds_(backgrounds) {}

    bool begin(QPaintDevice* device) override {
        device_ = device;
        return true;
    }
    bool end() override { return true; }
    Type type() const override { return QPaintEngine::User; }

    void updateState(const QPaintEngineState& s) override {
        const auto dirty = s.state();
        if (dirty & DirtyTransform) transform_ = s.transform();
        if (dirty & DirtyPen) pen_ = s.pen();
        if (dirty & DirtyBrush) brush_ = s.brush();
        if (dirty & DirtyClipEnabled) clipOn_ = s.isClipEnabled();
        if (dirty & (DirtyClipRegion | DirtyClipPath)) {
            const QRectF given =
                transform_.mapRect(dirty & DirtyClipRegion ? QRectF(s.clipRegion().boundingRect())
                                                           : s.clipPath().boundingRect());
            switch (s.clipOperation()) {
                case Qt::NoClip:
                    clipOn_ = false;
                    break;
                case Qt::ReplaceClip:
                    clip_ = given;
                    clipOn_ = true;
                    break;
                case Qt::IntersectClip:
                    clip_ = clipOn_ ? clip_ & given : given;
                    clipOn_ = true;
            }
        }
    }

    void drawTextItem(const QPointF& at, const QTextItem& item) override {
        if (!texts_ || item.text().trimmed().isEmpty()) return;
        const QFont font = item.font();
        const QFontMetricsF metrics(font, device_);
        const QRectF ink = metrics.tightBoundingRect(item.text()).translated(at);
        const double dpi = device_->logicalDpiY();
        const double points =
            font.pointSizeF() > 0 ? font.pointSizeF() : font.pixelSize() * 72.0 / dpi;
        const QRectF box = transform_.mapRect(ink);
        const bool cut = clipOn_ && !clip_.adjusted(-1, -1, 1, 1).contains(box);
        items_.texts.push_back({item.text(), box, points, false, cut});
    }
    void drawLines(const QLineF* lines, int n) override {
        for (int i = 0; i < n; ++i) segment(lines[i]);
    }
    void drawPolygon(const QPointF* points, int n, PolygonDrawMode mode) override {
        QPolygonF polygon;
        for (int i = 0; i < n; ++i) polygon << points[i];
        shape(polygon, mode != PolylineMode);
    }
    void drawPath(const QPainterPath& path) override {
        for (const QPolygonF& polygon : path.toSubpathPolygons())
            shape(polygon, polygon.isClosed() || brush_.style() != Qt::NoBrush);
    }
    void drawRects(const QRectF* rects, int n) override {
        for (int i = 0; i < n; ++i)
            if (!backgrounds_.contains(transform_.mapRect(rects[i])))
                shape(QPolygonF(rects[i]), true);
    }
    void drawEllipse(const QRectF& r) override { mark(r.center()); }
    void drawPoints(const QPointF* points, int n) override {
        for (int i = 0; i < n; ++i) mark(points[i]);
    }
    void drawPixmap(const QRectF&, const QPixmap&, const QRectF&) override {}
    void drawImage(const QRectF&, const QImage&, const QRectF&, Qt::ImageConversionFlags) override {
    }

private:
    bool penShows() const { return pen_.style() != Qt::NoPen && pen_.color().alpha() > 0; }
    bool brushShows() const { return brush_.style() != Qt::NoBrush && brush_.color().alpha() > 0; }
    void segment(const QLineF& given) {
        if (!data_ || !penShows()) return;
        const QLineF line = transform_.map(given);
        if (!clipOn_) {
            items_.segments << line;
        } else if (const auto inside = clipped(line, clip_)) {
            items_.segments << *inside;
        }
    }
    void mark(const QPointF& given) {
        if (!data_ || (!penShows() && !brushShows())) return;
        const QPointF at = transform_.map(given);
        if (!clipOn_ || clip_.contains(at)) items_.marks << at;
    }
    void shape(const QPolygonF& given, bool closed) {
        if (!data_ || given.size() < 2) return;
        for (int i = 1; i < given.size(); ++i) segment(QLineF(given[i - 1], given[i]));
        if (closed) segment(QLineF(given.back(), given.front()));
        if (closed && brushShows()) {
            QPolygonF area = transform_.map(given);
            if (clipOn_) area = area.intersected(QPolygonF(clip_));
            if (!area.isEmpty()) items_.areas << area;
        }
    }

    FigureItems& items_;
    bool texts_, data_;
    QList<QRectF> backgrounds_;
    QPaintDevice* device_ = nullptr;
    QTransform transform_;
    QPen pen_;
    QBrush brush_;
    QRectF clip_;
    bool clipOn_ = false;
};

class RecordingDevice : public QPaintDevice {
public:
    RecordingDevice(FigureItems& items, QSize size, int dpi, bool texts, bool data,
                    const QList<QRectF>& backgrounds)
        : engine_(items, texts, data, backgrounds), size_(size), dpi_(dpi) {}
    ~RecordingDevice() override = default;
    QPaintEngine* paintEngine() const override { return &engine_; }

protected:
    int metric(PaintDeviceMetric m) const override {
        switch (m) {
            case PdmWidth:
                return size_.width();
            case PdmHeight:
                return size_.height();
            case PdmWidthMM:
                return qRound(size_.width() * 25.4 / dpi_);
            case PdmHeightMM:
                return qRound(size_.height() * 25.4 / dpi_);
            case PdmDpiX:
            case PdmDpiY:
            case PdmPhysicalDpiX:
            case PdmPhysicalDpiY:
                return dpi_;
            case PdmDepth:
                return 32;
            case PdmNumColors:
                return INT_MAX;
            case PdmDevicePixelRatio:
                return 1;
            case PdmDevicePixelRatioScaled:
                return static_cast<int>(devicePixelRatioFScale());
            default:
                return 0;
        }
    }

private:
    mutable RecordingEngine engine_;
    QSize size_;
    int dpi_;
};

/// Paints `plot` at its size onto a recording device keeping texts or data.
void record(QCustomPlot& plot, FigureItems& items, bool texts, bool data,
            const QList<QRectF>& backgrounds) {
    RecordingDevice device(items, plot.viewport().size(), plot.logicalDpiY(), texts, data,
                           backgrounds);
    QCPPainter painter(&device);
    plot.toPainter(&painter, plot.viewport().width(), plot.viewport().height());
}

QString describe(const AuditText& t) {
    return QString("the text '%1' at (%2, %3)")
        .arg(t.text.left(40))
        .arg(t.box.center().x(), 0, 'f', 0)
        .arg(t.box.center().y(), 0, 'f', 0);
}

QString describe(const QRectF& legend) {
    return "the legend at " + boxText(legend);
}

/// The first piece of data inside `box`, described; empty if none.
QString dataUnder(const FigureItems& items, const QRectF& box, bool areasToo) {
    for (const QPointF& p : items.marks)
        if (box.contains(p))
            return QString("a plotted point at (%1, %2)")
                .arg(p.x(), 0, 'f', 0)
                .arg(p.y(), 0, 'f', 0);
    for (const QLineF& l : items.segments)
        if (clipped(l, box))
            return QString("a plotted line from (%1, %2) to (%3, %4)")
                .arg(l.x1(), 0, 'f', 0)
                .arg(l.y1(), 0, 'f', 0)
                .arg(l.x2(), 0, 'f', 0)
                .arg(l.y2(), 0, 'f', 0);
    if (areasToo)
        for (const QPolygonF& a : items.areas)
            if (!a.intersected(QPolygonF(box)).isEmpty())
                return QString("a plotted area at (%1, %2)")
                    .arg(a.boundingRect().center().x(), 0, 'f', 0)
                    .arg(a.boundingRect().center().y(), 0, 'f', 0);
    return {};
}

}  // namespace

namespace {
/// Hides or shows what is not data for the passes, without moving anything: an axis hidden would
/// give its margin to the panel, so axes only lose their lines (their text is not read in the
/// data's pass); titles, legends, colour scales and text items are hidden (a layout keeps their
/// room).
class DataOnly {
public:
    explicit DataOnly(QCustomPlot& plot) {
        for (QCPLayoutElement* e : plot.plotLayout()->elements(true)) {
            if (auto* rect = qobject_cast<QCPAxisRect*>(e)) {
                for (QCPAxis* axis : rect->axes()) axes_ << axis;
                for (QCPLayoutElement* inset : rect->insetLayout()->elements(true)) hide(inset);
            } else if (qobject_cast<QCPTextElement*>(e) || qobject_cast<QCPLegend*>(e)) {
                hide(e);
            } else if (auto* scale = qobject_cast<QCPColorScale*>(e)) {
                hide(scale);
            }
        }
        if (plot.legend) hide(plot.legend);
        for (int i = 0; i < plot.itemCount(); ++i)
            if (qobject_cast<QCPItemText*>(plot.item(i))) hide(plot.item(i));
        for (QCPAxis* axis : axes_) {
            pens_ << axis->basePen() << axis->tickPen() << axis->subTickPen() << axis->grid()->pen()
                  << axis->grid()->subGridPen() << axis->grid()->zeroLinePen();
            axis->setBasePen(Qt::NoPen);
            axis->setTickPen(Qt::NoPen);
            axis->setSubTickPen(Qt::NoPen);
            axis->grid()->setPen(Qt::NoPen);
            axis->grid()->setSubGridPen(Qt::NoPen);
            axis->grid()->setZeroLinePen(Qt::NoPen);
        }
    }
    ~DataOnly() {
        for (QCPLayerable* l : hidden_) l->setVisible(true);
        for (int i = 0; i < axes_.size(); ++i) {
            QCPAxis* axis = axes_[i];
            axis->setBasePen(pens_[6 * i]);
            axis->setTickPen(pens_[6 * i + 1]);
            axis->setSubTickPen(pens_[6 * i + 2]);
            axis->grid()->setPen(pens_[6 * i + 3]);
            axis->grid()->setSubGridPen(pens_[6 * i + 4]);
            axis->grid()->setZeroLinePen(pens_[6 * i + 5]);
        }
    }

private:
    void hide(QCPLayerable* l) {
        if (!l->visible() || hidden_.contains(l)) return;
        l->setVisible(false);
        hidden_ << l;
    }
    QList<QCPLayerable*> hidden_;
    QList<QCPAxis*> axes_;
    QList<QPen> pens_;
};

/// The data hidden for the texts' pass: plottables and every item but text.
class TextOnly {
public:
    /// With `legendsToo`, the legends are hidden as well (a layout keeps their room).
    TextOnly(QCustomPlot& plot, bool legendsToo) {
        for (int i = 0; i < plot.plottableCount(); ++i) hide(plot.plottable(i));
        for (int i = 0; i < plot.itemCount(); ++i)
            if (!qobject_cast<QCPItemText*>(plot.item(i))) hide(plot.item(i));
        if (!legendsToo) return;
        for (QCPLayoutElement* e : plot.plotLayout()->elements(true)) {
            if (auto* legend = qobject_cast<QCPLegend*>(e)) hide(legend);
            if (auto* rect = qobject_cast<QCPAxisRect*>(e))
                for (QCPLayoutElement* inset : rect->insetLayout()->elements(false))
                    if (auto* legend = qobject_cast<QCPLegend*>(inset)) hide(legend);
        }
        if (plot.legend) hide(plot.legend);
    }
    ~TextOnly() {
        for (QCPLayerable* l : hidden_) l->setVisible(true);
    }

private:
    void hide(QCPLayerable* l) {
        if (!l->visible()) return;
        l->setVisible(false);
        hidden_ << l;
    }
    QList<QCPLayerable*> hidden_;
};

QList<QRect> panelRects(QCustomPlot& plot) {
    QList<QRect> rects;
    for (QCPAxisRect* rect : plot.axisRects()) rects << rect->rect();
    return rects;
}
}  // namespace

FigureItems readFigureItems(QCustomPlot& plot) {
    FigureItems items;
    items.page = QRectF(plot.viewport());
    const QList<QRect> panels = panelRects(plot);
    // The figure's and the panels' backgrounds are not data.
    QList<QRectF> backgrounds{items.page};
    for (const QRect& r : panels) backgrounds << QRectF(r);
    {
        DataOnly hidden(plot);
        record(plot, items, false, true, backgrounds);
        items.layoutMoved = panelRects(plot) != panels;
    }
    // The texts: everything drawn but the data; those that are not drawn again without the
    // legends are the legends' own.
    FigureItems outsideLegends;
    {
        TextOnly hidden(plot, true);
        record(plot, outsideLegends, true, false, backgrounds);
    }
    {
        TextOnly hidden(plot, false);
        record(plot, items, true, false, backgrounds);
        items.layoutMoved = items.layoutMoved || panelRects(plot) != panels;
    }
    for (AuditText& t : items.texts)
        t.inLegend =
            std::none_of(outsideLegends.texts.begin(), outsideLegends.texts.end(),
                         [&](const AuditText& o) { return o.text == t.text && o.box == t.box; });
    plot.replot();

    for (QCPAxisRect* rect : plot.axisRects()) {
        items.panels << QRectF(rect->rect());
        for (QCPLayoutElement* e : rect->insetLayout()->elements(false))
            if (auto* legend = qobject_cast<QCPLegend*>(e);
                legend && legend->visible() && legend->itemCount() > 0)
                items.legends << QRectF(legend->outerRect());
    }
    return items;
}

QStringList auditFigure(const FigureItems& items, const QString& name, bool journal) {
    QStringList problems;
    auto problem = [&](const QString& what) { problems << QString("%1: %2").arg(name, what); };
    if (items.layoutMoved) problem("the figure's layout moved while it was read");
    const QVector<AuditText>& texts = items.texts;
    for (int i = 0; i < texts.size(); ++i) {
        const AuditText& t = texts[i];
        // Ink within half a pixel of another's counts as touching, not overlapping.
        const QRectF box = t.box.adjusted(0.5, 0.5, -0.5, -0.5);
        if (!items.page.adjusted(-0.5, -0.5, 0.5, 0.5).contains(t.box))
            problem(describe(t) + " runs off the page");
        else if (t.cut)
            problem(describe(t) + " is cut off by its panel's edge");
        if (journal && (t.points < 7.0 - 0.05 || t.points > 9.0 + 0.05))
            problem(describe(t) + QString(" is %1 pt (7-9 pt asked)").arg(t.points, 0, 'f', 2));
        for (int j = i + 1; j < texts.size(); ++j)
            if (box.intersects(texts[j].box.adjusted(0.5, 0.5, -0.5, -0.5)))
                problem(describe(t) + " overlaps " + describe(texts[j]));
        if (!t.inLegend)
            if (const QString under = dataUnder(items, box, false); !under.isEmpty())
                problem(describe(t) + " covers " + under);
    }
    for (const QRectF& legend : items.legends) {
        if (const QString under = dataUnder(items, legend, true); !under.isEmpty())
            problem(describe(legend) + " covers " + under);
        for (const AuditText& t : texts)
            if (!t.inLegend && legend.intersects(t.box))
                problem(describe(legend) + " overlaps " + describe(t));
    }
    return problems;
}

}  // namespace activetouch::test
