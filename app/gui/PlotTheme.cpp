#include "app/gui/PlotTheme.h"

#include <QMetaProperty>
#include <QPalette>
#include <algorithm>

#include "qcustomplot.h"

namespace activetouch {

namespace {
constexpr char kDarkInk[] = "darkInk";    ///< on the plot: the ink it was last put in
constexpr char kLightInk[] = "lightInk";  ///< on a part in dark ink: its light ink, to go back to
/// A dark plot's white is this light (0-1): the grey of a dark theme's view, not black.
constexpr double kDarkest = 0.13;

bool neutral(const QColor& c) {
    const QColor rgb = c.toRgb();
    const int spread = std::max({rgb.red(), rgb.green(), rgb.blue()}) -
                       std::min({rgb.red(), rgb.green(), rgb.blue()});
    return spread <= 24;
}

/// `c` at lightness `l` (0-1), its hue, saturation, alpha and spec kept.
QColor withLightness(const QColor& c, double l) {
    const QColor hsl = c.toHsl();
    return QColor::fromHslF(hsl.hslHueF(), hsl.hslSaturationF(), std::clamp(l, 0.0, 1.0),
                            hsl.alphaF())
        .convertTo(c.spec());
}

/// Light ink to dark: lightness l to kDarkest + (1 - kDarkest)(1 - l).
QColor darkened(const QColor& c) {
    if (!c.isValid() || !neutral(c)) return c;
    return withLightness(c, kDarkest + (1.0 - kDarkest) * (1.0 - c.lightnessF()));
}

/// A text's colour (QCustomPlot's colour properties are all texts'): a neutral one turned, a
/// dark coloured one lightened as much as it was dark, so that it reads on the dark page.
QColor darkenedText(const QColor& c) {
    if (!c.isValid() || neutral(c)) return darkened(c);
    const double l = c.lightnessF();
    return l >= 0.5 ? c : withLightness(c, 1.0 - l);
}

QPen darkened(QPen pen) {
    pen.setColor(darkened(pen.color()));
    return pen;
}

QBrush darkened(QBrush brush) {
    if (brush.style() != Qt::NoBrush && brush.style() < Qt::LinearGradientPattern)
        brush.setColor(darkened(brush.color()));
    return brush;
}

/// A graph's or a curve's scatter style (not a property QVariant carries).
QCPScatterStyle* scatterOf(QObject* object, QCPScatterStyle& copy) {
    if (auto* g = qobject_cast<QCPGraph*>(object)) return &(copy = g->scatterStyle());
    if (auto* c = qobject_cast<QCPCurve*>(object)) return &(copy = c->scatterStyle());
    return nullptr;
}

void setScatter(QObject* object, const QCPScatterStyle& style) {
    if (auto* g = qobject_cast<QCPGraph*>(object)) g->setScatterStyle(style);
    if (auto* c = qobject_cast<QCPCurve*>(object)) c->setScatterStyle(style);
}

/// `object`'s colour, pen and brush properties (QCustomPlot declares each as a Q_PROPERTY) and
/// its scatter style's pen and brush, by name.
QVariantMap inkOf(QObject* object) {
    QVariantMap ink;
    const QMetaObject* meta = object->metaObject();
    // A legend's text colours are set on its items as well: the items' own are theirs.
    const bool legend = qobject_cast<QCPLegend*>(object) != nullptr;
    for (int i = 0; i < meta->propertyCount(); ++i) {
        const QMetaProperty p = meta->property(i);
        const int type = p.metaType().id();
        if (legend && QByteArray(p.name()).endsWith("extColor")) continue;
        if (p.isWritable() &&
            (type == QMetaType::QColor || type == QMetaType::QPen || type == QMetaType::QBrush))
            ink.insert(p.name(), p.read(object));
    }
    QCPScatterStyle scatter;
    if (scatterOf(object, scatter)) {
        ink.insert(" scatterPen", scatter.pen());
        ink.insert(" scatterBrush", scatter.brush());
    }
    return ink;
}

void setInk(QObject* object, const QVariantMap& ink) {
    QCPScatterStyle scatter;
    const bool scatters = scatterOf(object, scatter);
    for (auto it = ink.cbegin(); it != ink.cend(); ++it) {
        if (it.key() == " scatterPen" && scatters)
            scatter.setPen(it.value().value<QPen>());
        else if (it.key() == " scatterBrush" && scatters)
            scatter.setBrush(it.value().value<QBrush>());
        else
            object->setProperty(it.key().toUtf8().constData(), it.value());
    }
    if (scatters) setScatter(object, scatter);
}

QVariant darkOf(const QVariant& v) {
    switch (v.metaType().id()) {
        case QMetaType::QColor:
            return darkenedText(v.value<QColor>());
        case QMetaType::QPen:
            return darkened(v.value<QPen>());
        case QMetaType::QBrush:
            return darkened(v.value<QBrush>());
        default:
            return v;
    }
}

/// Into dark ink, its light ink kept; back, the light ink put back as it was.
void turnObject(QObject* object, bool toDark) {
    if (toDark) {
        const QVariantMap light = inkOf(object);
        QVariantMap dark;
        for (auto it = light.cbegin(); it != light.cend(); ++it)
            dark.insert(it.key(), darkOf(it.value()));
        object->setProperty(kLightInk, light);
        setInk(object, dark);
    } else {
        setInk(object, object->property(kLightInk).toMap());
        object->setProperty(kLightInk, QVariant());
    }
}
}  // namespace

bool isDarkPalette(const QPalette& palette) {
    return palette.color(QPalette::Window).lightnessF() <
           palette.color(QPalette::WindowText).lightnessF();
}

void setDarkInk(QCustomPlot& plot, bool dark) {
    // A plot never put in dark ink has every part in light ink: nothing to look at (the light
    // theme's replots cost nothing). Every part of a plot (axes, grids, layout elements, legends
    // and their items, plottables, items) is a QObject child of the plot; one in dark ink keeps
    // its light ink.
    if (!dark && !inDarkInk(plot)) return;
    for (QCPLayerable* part : plot.findChildren<QCPLayerable*>())
        if (part->property(kLightInk).isValid() != dark) turnObject(part, dark);
    // The figure's page is white (FigureLayout sets it with each figure drawn anew); dark, the
    // grey its white turns to.
    plot.setBackground(dark ? darkened(QColor(Qt::white)) : QColor(Qt::white));
    plot.setProperty(kDarkInk, dark);
}

bool inDarkInk(const QCustomPlot& plot) {
    return plot.property(kDarkInk).toBool();
}

}  // namespace activetouch
