#include "app/gui/PlotReadout.h"

#include <QRegularExpression>
#include <QStringList>
#include <algorithm>
#include <cmath>

#include "qcustomplot.h"

namespace activetouch {

QPair<QString, QString> quantityOf(const QString& label) {
    static const QRegularExpression unit(R"(^(.*?)\s*\(([^()]*)\)\s*$)");
    const QRegularExpressionMatch m = unit.match(label);
    if (m.hasMatch()) return {m.captured(1), m.captured(2)};
    return {label, QString()};
}

QString readoutNumber(double v) {
    if (!std::isfinite(v)) return QString::number(v);
    const double magnitude = std::abs(v);
    if (magnitude >= 1000.0 && magnitude < 1e9) return QString::number(std::round(v), 'f', 0);
    const QString text = QString::number(v, 'g', 4);
    return text == "-0" ? QString("0") : text;
}

namespace {
QString firstLine(const QString& label) {
    return label.section('\n', 0, 0).trimmed();
}
}  // namespace

QString categoryAt(const QCPAxis* axis, double v) {
    if (!axis || !std::isfinite(v)) return {};
    const double nearest = std::round(v);
    if (std::abs(nearest) > 1e6) return {};
    const QVariant names = axis->property(kCategoryNames);
    if (names.isValid()) {
        const QStringList list = names.toStringList();
        const auto k = static_cast<qsizetype>(nearest);
        return k >= 0 && k < list.size() ? list[k] : QString();
    }
    const auto text = axis->ticker().dynamicCast<QCPAxisTickerText>();
    if (!text || text->ticks().isEmpty()) return {};
    const QMap<double, QString>& ticks = text->ticks();
    bool consecutive = true;
    double previous = ticks.firstKey() - 1.0;
    for (auto it = ticks.cbegin(); it != ticks.cend() && consecutive; ++it) {
        consecutive = it.key() == std::round(it.key()) && it.key() == previous + 1.0;
        previous = it.key();
    }
    if (consecutive) return ticks.contains(nearest) ? firstLine(ticks.value(nearest)) : QString();
    const double tolerance = 1e-9 * std::max(1.0, std::abs(v));
    for (auto it = ticks.cbegin(); it != ticks.cend(); ++it)
        if (std::abs(it.key() - v) <= tolerance) return firstLine(it.value());
    return {};
}

QString axisValueText(const QCPAxis* axis, double v) {
    const auto [name, unit] = quantityOf(axis->label());
    const QString quantity = name.isEmpty() ? QString("x") : name;
    const QString category = categoryAt(axis, v);
    if (!category.isEmpty()) return quantity + " " + category;
    return QString("%1 %2%3").arg(quantity, readoutNumber(v),
                                  unit.isEmpty() ? QString() : " " + unit);
}

QRectF readoutPlace(const QRectF& plot, const QPointF& cursor, const QSizeF& size) {
    constexpr double gap = 12.0, edge = 8.0;
    double left = cursor.x() + gap;
    if (left + size.width() > plot.right() - edge) left = cursor.x() - gap - size.width();
    double top = cursor.y() - gap - size.height();
    if (top < plot.top() + edge) top = cursor.y() + gap;
    // A plot too small for either side: the label as far in as it goes, its top-left kept.
    left = std::clamp(left, plot.left() + edge,
                      std::max(plot.left() + edge, plot.right() - edge - size.width()));
    top = std::clamp(top, plot.top() + edge,
                     std::max(plot.top() + edge, plot.bottom() - edge - size.height()));
    return QRectF(QPointF(left, top), size);
}

}  // namespace activetouch
