#include "app/figures/FigureExport.h"

#include <QDir>
#include <QFileInfo>
#include <QPageSize>
#include <QPdfWriter>
#include <QSvgGenerator>
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "app/figures/FigureFitting.h"
#include "app/figures/FigureLayout.h"
#include "app/figures/FigureReflow.h"
#include "qcustomplot.h"

namespace activetouch {

void setEqualAspectRanges(QCPAxisRect* rect, const QCPRange& x, const QCPRange& y) {
    rect->setProperty("equalAspectX", QPointF(x.lower, x.upper));
    rect->setProperty("equalAspectY", QPointF(y.lower, y.upper));
    rect->axis(QCPAxis::atBottom)->setRange(x);
    rect->axis(QCPAxis::atLeft)->setRange(y);
}

void keepLegendClear(QCPAxisRect* rect, QCPLegend* legend, double dataRight, double dataTop) {
    rect->setProperty("legendClearOf", QPointF(dataRight, dataTop));
    rect->setProperty("legendToKeepClear", QVariant::fromValue<QObject*>(legend));
}

namespace {
/// `wantX` and `wantY` shown at one unit per pixel in `rect`: the one that would be stretched
/// widened about its centre.
std::pair<QCPRange, QCPRange> equalAspect(const QCPAxisRect* rect, QCPRange x, QCPRange y) {
    const double xPerPixel = x.size() / rect->width(), yPerPixel = y.size() / rect->height();
    if (xPerPixel >= yPerPixel) {
        const double half = 0.5 * xPerPixel * rect->height();
        y = QCPRange(y.center() - half, y.center() + half);
    } else {
        const double half = 0.5 * yPerPixel * rect->width();
        x = QCPRange(x.center() - half, x.center() + half);
    }
    return {x, y};
}
}  // namespace

bool fitEqualAspect(QCustomPlot& plot) {
    bool changed = false;
    for (QCPAxisRect* rect : plot.axisRects()) {
        const QVariant wantX = rect->property("equalAspectX"),
                       wantY = rect->property("equalAspectY");
        if (!wantX.isValid() || !wantY.isValid()) continue;
        if (rect->width() <= 0 || rect->height() <= 0) continue;
        // Keep both ranges asked for visible: widen the one that would otherwise be stretched.
        const QCPRange askedX(wantX.toPointF().x(), wantX.toPointF().y());
        QCPRange askedY(wantY.toPointF().x(), wantY.toPointF().y());
        auto [x, y] = equalAspect(rect, askedX, askedY);
        // A legend in the top right corner: beside the data if the shape leaves room there,
        // else above it, the view's top raised until it fits.
        auto* legend =
            qobject_cast<QCPLegend*>(rect->property("legendToKeepClear").value<QObject*>());
        const QVariant clear = rect->property("legendClearOf");
        for (int round = 0; legend && clear.isValid() && round < 4; ++round) {
            const QSize needs = legend->minimumOuterSizeHint() + QSize(12, 12);
            const double perPixel = x.size() / rect->width();
            const double besideData = (x.upper - clear.toPointF().x()) / perPixel;
            const double aboveData = (y.upper - clear.toPointF().y()) / perPixel;
            if (besideData >= needs.width() || aboveData >= needs.height()) break;
            askedY.upper = clear.toPointF().y() + needs.height() * perPixel * 1.05;
            std::tie(x, y) = equalAspect(rect, askedX, askedY);
        }
        // What was asked for after the legend's room: the range shown in full on one axis.
        rect->setProperty("equalAspectShownY", QPointF(askedY.lower, askedY.upper));
        QCPAxis* xAxis = rect->axis(QCPAxis::atBottom);
        QCPAxis* yAxis = rect->axis(QCPAxis::atLeft);
        auto same = [](const QCPRange& a, const QCPRange& b) {
            const double tolerance = 1e-9 * std::max(1.0, a.size());
            return std::abs(a.lower - b.lower) <= tolerance &&
                   std::abs(a.upper - b.upper) <= tolerance;
        };
        if (same(xAxis->range(), x) && same(yAxis->range(), y)) continue;
        xAxis->setRange(x);
        yAxis->setRange(y);
        changed = true;
    }
    return changed;
}

namespace {
/// The plot's logical resolution: what its fonts' point sizes are turned into pixels at.
double logicalDpi(const QCustomPlot& plot) {
    const int dpi = plot.logicalDpiX();
    return dpi > 0 ? dpi : 96.0;
}

/// The size a physical figure is laid out at: its size in the plot's logical pixels.
QSize logicalSize(const QCustomPlot& plot, const FigureSize& size) {
    const double dpi = logicalDpi(plot);
    return {static_cast<int>(std::lround(size.width_mm / 25.4 * dpi)),
            static_cast<int>(std::lround(size.height_mm / 25.4 * dpi))};
}

double pointsOf(const QFont& font, double dpi) {
    return font.pointSizeF() > 0 ? font.pointSizeF() : font.pixelSize() * 72.0 / dpi;
}
}  // namespace

std::function<void()> setJournalText(QCustomPlot& plot) {
    const double dpi = logicalDpi(plot);
    // Every font a figure draws text with, as a getter and a setter, each once: a legend inside a
    // panel is reached through the panel and again through the layout's elements.
    struct Text {
        std::function<QFont()> get;
        std::function<void(const QFont&)> set;
    };
    std::vector<Text> texts;
    std::set<std::pair<const void*, int>> seen;
    auto add = [&](const void* owner, int which, Text t) {
        if (seen.insert({owner, which}).second) texts.push_back(std::move(t));
    };
    auto axis = [&](QCPAxis* a) {
        add(a, 0, {[a] { return a->labelFont(); }, [a](const QFont& f) { a->setLabelFont(f); }});
        add(a, 1,
            {[a] { return a->tickLabelFont(); }, [a](const QFont& f) { a->setTickLabelFont(f); }});
        add(a, 2,
            {[a] { return a->selectedLabelFont(); },
             [a](const QFont& f) { a->setSelectedLabelFont(f); }});
        add(a, 3,
            {[a] { return a->selectedTickLabelFont(); },
             [a](const QFont& f) { a->setSelectedTickLabelFont(f); }});
    };
    auto legendItems = [&](QCPLegend* legend) {
        for (int i = 0; i < legend->itemCount(); ++i)
            if (QCPAbstractLegendItem* item = legend->item(i))
                add(item, 0,
                    {[item] { return item->font(); },
                     [item](const QFont& f) { item->setFont(f); }});
    };
    for (QCPLayoutElement* e : plot.plotLayout()->elements(true)) {
        if (auto* rect = qobject_cast<QCPAxisRect*>(e)) {
            for (QCPAxis* a : rect->axes()) axis(a);
            for (QCPLayoutElement* inset : rect->insetLayout()->elements(true))
                if (auto* legend = qobject_cast<QCPLegend*>(inset)) legendItems(legend);
        } else if (auto* scale = qobject_cast<QCPColorScale*>(e)) {
            axis(scale->axis());
        } else if (auto* title = qobject_cast<QCPTextElement*>(e)) {
            add(title, 0,
                {[title] { return title->font(); },
                 [title](const QFont& f) { title->setFont(f); }});
        } else if (auto* legend = qobject_cast<QCPLegend*>(e)) {
            legendItems(legend);
        }
    }
    // Legends inside panels are in the panels' inset layouts, and so reached above; the plot's
    // own legend may be anywhere.
    if (plot.legend) legendItems(plot.legend);
    for (int i = 0; i < plot.itemCount(); ++i)
        if (auto* text = qobject_cast<QCPItemText*>(plot.item(i)))
            add(text, 0,
                {[text] { return text->font(); }, [text](const QFont& f) { text->setFont(f); }});

    double largest = 0.0;
    for (const Text& t : texts) largest = std::max(largest, pointsOf(t.get(), dpi));
    std::vector<std::pair<std::function<void(const QFont&)>, QFont>> before;
    if (largest <= 0.0) return [] {};
    const double factor = kLargestText_pt / largest;
    for (const Text& t : texts) {
        const QFont old = t.get();
        before.emplace_back(t.set, old);
        QFont f = old;
        f.setPointSizeF(std::clamp(pointsOf(old, dpi) * factor, kSmallestText_pt, kLargestText_pt));
        t.set(f);
    }
    return [before] {
        for (const auto& [set, font] : before) set(font);
    };
}

namespace {
/// Lays `plot` out at the physical `size` with journal text; returns what puts the fonts back.
std::function<void()> layOutPhysical(QCustomPlot& plot, const FigureSize& size);
}  // namespace

void layOutAt(QCustomPlot& plot, const FigureSize& asked) {
    if (asked.isPhysical()) {
        layOutPhysical(plot, asked);
        return;
    }
    const FigureSize& size = asked;
    plot.resize(size.width_px, size.height_px);
    plot.setViewport(QRect(0, 0, size.width_px, size.height_px));
    plot.replot(QCustomPlot::rpImmediateRefresh);
    // A refit can move margins and so the panels' shapes again; a few rounds settle it.
    for (int round = 0; round < kLayoutRounds && fitToLayout(plot); ++round)
        plot.replot(QCustomPlot::rpImmediateRefresh);
}

namespace {
void layOutPixels(QCustomPlot& plot, const QSize& size) {
    plot.resize(size);
    plot.setViewport(QRect(QPoint(0, 0), size));
    plot.replot(QCustomPlot::rpImmediateRefresh);
    for (int round = 0; round < kLayoutRounds && fitToLayout(plot); ++round)
        plot.replot(QCustomPlot::rpImmediateRefresh);
}

std::function<void()> layOutPhysical(QCustomPlot& plot, const FigureSize& size) {
    // Labels wrap to their panels with every fit (fitToLayout), as on screen.
    const std::function<void()> fonts = setJournalText(plot);
    layOutPixels(plot, logicalSize(plot, size));
    return fonts;
}
}  // namespace

QString figuresDirectory(const QString& outDir) {
    const QString dir = outDir + "/figures";
    if (!QDir().mkpath(dir))
        throw std::runtime_error("cannot create " + dir.toStdString() +
                                 "; check the output folder is writable");
    return dir;
}

namespace {
/// Writes `plot`, laid out at `layout` (its logical pixels), in each format as
/// <basePath>.<format>: the PNG `pngScale` times larger with `dpi` recorded; the PDF at `pageMm`
/// (a physical size) or one point per pixel (QCustomPlot's own); the SVG at `svgDpi`.
QStringList writeFormats(QCustomPlot& plot, const QString& basePath, const QStringList& formats,
                         QSize layout, double pngScale, int dpi, QSizeF pageMm, int svgDpi) {
    QStringList written;
    const int w = layout.width(), h = layout.height();
    const QString title = QFileInfo(basePath).baseName();
    for (const QString& format : formats) {
        const QString file = basePath + "." + format.toLower();
        bool ok = false;
        if (format.compare("png", Qt::CaseInsensitive) == 0) {
            ok = plot.savePng(file, w, h, pngScale, -1, dpi, QCP::ruDotsPerInch);
        } else if (format.compare("pdf", Qt::CaseInsensitive) == 0 && pageMm.isEmpty()) {
            ok = plot.savePdf(file, w, h, QCP::epNoCosmetic, "ActiveTouch Workbench", title);
        } else if (format.compare("pdf", Qt::CaseInsensitive) == 0) {
            QPdfWriter pdf(file);
            pdf.setCreator("ActiveTouch Workbench");
            pdf.setTitle(title);
            pdf.setResolution(svgDpi);
            ok = pdf.setPageLayout(QPageLayout(
                QPageSize(pageMm, QPageSize::Millimeter, QString(), QPageSize::ExactMatch),
                QPageLayout::Portrait, QMarginsF(0, 0, 0, 0)));
            QCPPainter painter;
            ok = ok && painter.begin(&pdf);
            if (ok) {
                painter.setMode(QCPPainter::pmVectorized);
                painter.setMode(QCPPainter::pmNoCaching);
                painter.setMode(QCPPainter::pmNonCosmetic);
                plot.toPainter(&painter, w, h);
                ok = painter.end();
            }
        } else if (format.compare("svg", Qt::CaseInsensitive) == 0) {
            QSvgGenerator svg;
            svg.setFileName(file);
            svg.setResolution(svgDpi);
            svg.setSize(QSize(w, h));
            svg.setViewBox(QRect(0, 0, w, h));
            svg.setTitle(title);
            QCPPainter painter;
            ok = painter.begin(&svg);
            if (ok) {
                painter.setMode(QCPPainter::pmVectorized);
                plot.toPainter(&painter, w, h);
                ok = painter.end();
            }
        } else {
            throw std::runtime_error("unknown figure format '" + format.toStdString() +
                                     "'; use png, pdf or svg");
        }
        if (!ok || !QFileInfo(file).exists() || QFileInfo(file).size() == 0)
            throw std::runtime_error("could not write " + file.toStdString() +
                                     "; check the folder is writable");
        written << file;
    }
    return written;
}
}  // namespace

FigureSize figureSizeFor(QCustomPlot& plot, const FigureSize& usual, double widthMm) {
    const double usualHeight =
        usual.isPhysical() ? usual.height_mm : kDoubleColumn_mm * usual.height_px / usual.width_px;
    const FigureSize first = FigureSize::physical(widthMm, usualHeight, usual.dpi);
    layOutAt(plot, first);
    FigureSize fitted = FigureSize::physical(widthMm, usualHeight * reflowGrowth(plot), usual.dpi);
    layOutAt(plot, fitted);
    // Never shorter than its parts need (panels and texts with a least height, a caption's lines).
    const double mmPerPixel = 25.4 / logicalDpi(plot);
    const double least = plot.plotLayout()->minimumOuterSizeHint().height() * mmPerPixel + 2.0;
    if (least > fitted.height_mm) {
        fitted = FigureSize::physical(widthMm, least, usual.dpi);
        layOutAt(plot, fitted);
    }
    return fitted;
}

QSize layoutSize(const QCustomPlot& plot, const FigureSize& size) {
    return size.isPhysical() ? logicalSize(plot, size) : QSize(size.width_px, size.height_px);
}

QStringList exportFigure(QCustomPlot& plot, const QString& basePath, const QStringList& formats,
                         const FigureSize& size) {
    if (!size.isPhysical()) {
        // Lay out once at the target size so that every format sees the same geometry.
        layOutAt(plot, size);
        return writeFormats(plot, basePath, formats, layoutSize(plot, size), 1.0, size.dpi, {},
                            size.dpi);
    }
    // A physical size: the PNG scaled to be the size's own pixels wide, the PDF and SVG at the
    // size itself, their text as the fonts' point sizes.
    const std::function<void()> restore = layOutPhysical(plot, size);
    try {
        const QSize layout = layoutSize(plot, size);
        QStringList written = writeFormats(
            plot, basePath, formats, layout, double(size.width_px) / layout.width(), size.dpi,
            QSizeF(size.width_mm, size.height_mm), static_cast<int>(logicalDpi(plot)));
        restore();
        return written;
    } catch (...) {
        restore();
        throw;
    }
}

}  // namespace activetouch
