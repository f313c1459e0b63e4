#include "app/figures/FigureFitting.h"

#include <QFontMetricsF>
#include <algorithm>
#include <cmath>
#include <functional>

#include "app/figures/FigureExport.h"
#include "app/figures/FigureLayout.h"
#include "app/figures/FigureReflow.h"
#include "qcustomplot.h"

namespace activetouch {

QSizeF textSize(const QCPItemText& label) {
    return QFontMetricsF(label.font())
        .boundingRect(QRectF(), Qt::TextDontClip, label.text())
        .size();
}

/// `text` broken into lines at spaces so that none is wider than `room` pixels in `font` (a word
/// wider than the room keeps its own line).
QString wrapped(const QString& text, const QFont& font, double room) {
    const QFontMetricsF metrics(font);
    QStringList lines;
    for (const QString& given : text.split('\n')) {
        QString line;
        for (const QString& word : given.split(' ', Qt::SkipEmptyParts)) {
            const QString longer = line.isEmpty() ? word : line + ' ' + word;
            if (!line.isEmpty() && metrics.horizontalAdvance(longer) > room) {
                lines << line;
                line = word;
            } else {
                line = longer;
            }
        }
        lines << line;
    }
    return lines.join('\n');
}

namespace {
/// `current`, the text `owner` shows, wrapped to `room` from the text the figure's code gave it
/// (kept as a property of `owner`, so that more room unwraps it again; text the code set since
/// the last wrapping is the new original); `show` shows a new wrapping. Whether it changed.
bool rewrapped(QObject* owner, const QString& current, const QFont& font, double room,
               const std::function<void(const QString&)>& show) {
    if (current != owner->property("wrappedText").toString())
        owner->setProperty("unwrappedText", current);
    const QString fitted = wrapped(owner->property("unwrappedText").toString(), font, room);
    owner->setProperty("wrappedText", fitted);
    if (fitted == current) return false;
    show(fitted);
    return true;
}

/// The figure's title and caption wrapped to the plot's width, from the text the figure's code
/// gave them (kept as a property, so that a wider plot unwraps them again). Whether any changed.
bool wrapFigureText(QCustomPlot& plot) {
    bool changed = false;
    const double room = plot.viewport().width() - 8.0;
    if (room <= 20) return false;
    for (QCPLayoutElement* e : plot.plotLayout()->elements(false)) {
        auto* text = qobject_cast<QCPTextElement*>(e);
        if (!text) continue;
        changed = rewrapped(text, text->text(), text->font(), room,
                            [text](const QString& t) { text->setText(t); }) ||
                  changed;
    }
    return changed;
}
}  // namespace

namespace {
/// The entries of every legend inside a panel wrapped to the panel's width, where the legend
/// would be wider than the data it sits over: a plottable's name is its entry, so the name is
/// wrapped and the figure's own kept (seriesName). Whether any changed.
bool wrapInsideLegends(QCustomPlot& plot) {
    bool changed = false;
    for (QCPAxisRect* rect : plot.axisRects())
        for (QCPLayoutElement* e : rect->insetLayout()->elements(false)) {
            auto* legend = qobject_cast<QCPLegend*>(e);
            if (!legend || !legend->visible()) continue;
            const double room = rect->width() - 12.0 - legend->iconSize().width() -
                                legend->iconTextPadding() - legend->margins().left() -
                                legend->margins().right() - 8.0;
            if (room <= 40) continue;
            for (int i = 0; i < legend->itemCount(); ++i) {
                auto* item = qobject_cast<QCPPlottableLegendItem*>(legend->item(i));
                if (!item || !item->plottable()) continue;
                QCPAbstractPlottable* p = item->plottable();
                changed = rewrapped(p, p->name(), item->font(), room,
                                    [p](const QString& t) { p->setName(t); }) ||
                          changed;
            }
        }
    return changed;
}

/// Every axis label wrapped to its panel's length along it, from the text the figure's code gave
/// it (kept as a property, so that a larger panel unwraps it again). Whether any changed.
bool wrapAxisLabels(QCustomPlot& plot) {
    bool changed = false;
    for (QCPAxisRect* rect : plot.axisRects())
        for (QCPAxis* axis : rect->axes()) {
            const double room =
                axis->orientation() == Qt::Horizontal ? rect->width() : rect->height();
            if (room <= 20 || axis->label().isEmpty()) continue;
            changed = rewrapped(axis, axis->label(), axis->labelFont(), room,
                                [axis](const QString& t) { axis->setLabel(t); }) ||
                      changed;
        }
    return changed;
}

/// The widest of `labels` in `font`, and the tallest line.
QSizeF widestLabel(const QVector<QString>& labels, const QFont& font) {
    const QFontMetricsF metrics(font);
    QSizeF most;
    for (const QString& l : labels) {
        const QRectF r = metrics.boundingRect(QRectF(), Qt::TextDontClip, l);
        most = most.expandedTo(r.size());
    }
    return most;
}

/// Every panel's axes and every colour scale's, whose ticks are thinned: not named ticks (shapes,
/// orientations), which stay as they are.
QList<QCPAxis*> thinnableAxes(QCustomPlot& plot) {
    QList<QCPAxis*> all, axes;
    for (QCPAxisRect* rect : plot.axisRects()) all << rect->axes();
    for (QCPLayoutElement* e : plot.plotLayout()->elements(true))
        if (auto* scale = qobject_cast<QCPColorScale*>(e)) all << scale->axis();
    for (QCPAxis* axis : all) {
        const QSharedPointer<QCPAxisTicker> ticker = axis->ticker();
        if (axis->visible() && axis->tickLabels() && ticker &&
            !ticker.dynamicCast<QCPAxisTickerText>())
            axes << axis;
    }
    return axes;
}

/// Keeps the ticks the figure's code asked for on `axis` (as properties, the first time) and, if
/// `putBack`, puts them back. Whether they changed.
bool askedTicks(QCPAxis* axis, bool putBack) {
    QSharedPointer<QCPAxisTicker> ticker = axis->ticker();
    if (auto fixed = ticker.dynamicCast<QCPAxisTickerFixed>()) {
        if (!axis->property("askedTickStep").isValid()) {
            axis->setProperty("askedTickStep", fixed->tickStep());
            axis->setProperty("askedScaleStrategy", int(fixed->scaleStrategy()));
        }
        const double step = axis->property("askedTickStep").toDouble();
        const auto strategy =
            QCPAxisTickerFixed::ScaleStrategy(axis->property("askedScaleStrategy").toInt());
        if (!putBack || (fixed->tickStep() == step && fixed->scaleStrategy() == strategy))
            return false;
        fixed->setTickStep(step);
        fixed->setScaleStrategy(strategy);
        return true;
    }
    if (!axis->property("askedTickCount").isValid())
        axis->setProperty("askedTickCount", ticker->tickCount());
    const int count = axis->property("askedTickCount").toInt();
    if (!putBack || ticker->tickCount() == count) return false;
    ticker->setTickCount(count);
    return true;
}

/// Back to more ticks only with room to spare: fewer ticks can mean narrower labels, which must
/// not let the ticks back and so on.
constexpr double kMoreRoom = 1.25;

/// `axis`'s ticks thinned until its labels, `needed` pixels each along it, have room over its
/// `length`. Whether they changed.
bool thinnedTicks(QCPAxis* axis, double length, double needed) {
    QSharedPointer<QCPAxisTicker> ticker = axis->ticker();
    if (auto fixed = ticker.dynamicCast<QCPAxisTickerFixed>()) {
        const double asked = axis->property("askedTickStep").toDouble();
        const double perUnit = std::abs(axis->coordToPixel(1.0) - axis->coordToPixel(0.0));
        auto doublings = [&](double need) {
            double factor = 1.0;
            while (asked * factor * perUnit < need && factor < 1e6) factor *= 2.0;
            return factor;
        };
        const double now = fixed->tickStep() / asked;
        double factor = doublings(needed);
        if (factor < now) factor = std::min(now, doublings(needed * kMoreRoom));
        const auto strategy =
            factor > 1.0
                ? QCPAxisTickerFixed::ssNone
                : QCPAxisTickerFixed::ScaleStrategy(axis->property("askedScaleStrategy").toInt());
        if (fixed->tickStep() == asked * factor && fixed->scaleStrategy() == strategy) return false;
        fixed->setTickStep(asked * factor);
        fixed->setScaleStrategy(strategy);
        return true;
    }
    // An automatic ticker rounds its step to a nice one (1, 2, 2.5, 5 times a power of ten),
    // which can put up to twice the count asked for along the axis.
    const int asked = axis->property("askedTickCount").toInt();
    auto countFor = [&](double need) {
        return std::clamp(static_cast<int>(std::floor(length / (2.0 * need))), 2, asked);
    };
    int count = countFor(needed);
    if (count > ticker->tickCount())
        count = std::max(ticker->tickCount(), countFor(needed * kMoreRoom));
    if (ticker->tickCount() == count) return false;
    ticker->setTickCount(count);
    return true;
}

/// Tick labels that would run together thinned, always from the ticks the figure's code asked
/// for (a new size, `fresh`, starts from them again, so a roomier plot gets them back). Whether
/// any changed.
bool fitTicks(QCustomPlot& plot, bool fresh) {
    bool changed = false;
    for (QCPAxis* axis : thinnableAxes(plot)) {
        if (askedTicks(axis, fresh)) changed = true;
        if (fresh) continue;  // put back; the next round measures them
        const bool across = axis->orientation() == Qt::Horizontal;
        const double length = across ? axis->axisRect()->width() : axis->axisRect()->height();
        if (length <= 0) continue;
        // The labels need the room of the widest shown; an axis thinned to no label at all (at a
        // size too small for one) that of its range's ends, written as the axis writes numbers.
        QVector<QString> labels = axis->tickVectorLabels();
        if (labels.isEmpty()) {
            const QLocale locale = axis->parentPlot()->locale();
            const QString format = axis->numberFormat();
            const char letter = format.isEmpty() ? 'g' : format.at(0).toLatin1();
            for (const double end : {axis->range().lower, axis->range().upper})
                labels << locale.toString(end, letter, axis->numberPrecision());
        }
        const QSizeF label = widestLabel(labels, axis->tickLabelFont());
        changed =
            thinnedTicks(axis, length, (across ? label.width() : label.height()) + 4.0) || changed;
    }
    return changed;
}
}  // namespace

bool fitToLayout(QCustomPlot& plot) {
    // The first round at a size fits afresh; the rounds after it only settle (FigureReflow.h).
    const QSize size = plot.viewport().size();
    const bool fresh = plot.property("fittedAt").toSize() != size;
    plot.setProperty("fittedAt", size);
    const bool panels = reflowPanels(plot, fresh);
    const bool headroom = fitHeadroom(plot);
    const bool scales = fitColourScales(plot);
    const bool points = placePointLabels(plot);
    const bool legends = fitLegendLines(plot);
    const bool text = wrapFigureText(plot);
    const bool labels = wrapAxisLabels(plot) | wrapInsideLegends(plot);
    const bool ticks = fitTicks(plot, fresh);
    return fitEqualAspect(plot) || panels || headroom || scales || points || legends || text ||
           labels || ticks;
}

QString seriesName(const QCPAbstractPlottable* plottable) {
    const QVariant given = plottable->property("unwrappedText");
    return given.isValid() ? given.toString() : plottable->name();
}

}  // namespace activetouch
