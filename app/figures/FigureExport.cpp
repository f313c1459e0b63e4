#include "app/figures/FigureExport.h"

#include <QDir>
#include <QFileInfo>
#include <QSvgGenerator>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "app/figures/FigureLayout.h"
#include "qcustomplot.h"

namespace activetouch {

void setEqualAspectRanges(QCPAxisRect* rect, const QCPRange& x, const QCPRange& y) {
    rect->setProperty("equalAspectX", QPointF(x.lower, x.upper));
    rect->setProperty("equalAspectY", QPointF(y.lower, y.upper));
    rect->axis(QCPAxis::atBottom)->setRange(x);
    rect->axis(QCPAxis::atLeft)->setRange(y);
}

bool fitEqualAspect(QCustomPlot& plot) {
    bool changed = false;
    for (QCPAxisRect* rect : plot.axisRects()) {
        const QVariant wantX = rect->property("equalAspectX"),
                       wantY = rect->property("equalAspectY");
        if (!wantX.isValid() || !wantY.isValid()) continue;
        if (rect->width() <= 0 || rect->height() <= 0) continue;
        // Keep both ranges asked for visible: widen the one that would otherwise be stretched.
        QCPRange x(wantX.toPointF().x(), wantX.toPointF().y());
        QCPRange y(wantY.toPointF().x(), wantY.toPointF().y());
        const double xPerPixel = x.size() / rect->width(), yPerPixel = y.size() / rect->height();
        if (xPerPixel >= yPerPixel) {
            const double half = 0.5 * xPerPixel * rect->height();
            y = QCPRange(y.center() - half, y.center() + half);
        } else {
            const double half = 0.5 * yPerPixel * rect->width();
            x = QCPRange(x.center() - half, x.center() + half);
        }
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

bool fitToLayout(QCustomPlot& plot) {
    const bool legends = fitLegendLines(plot);
    return fitEqualAspect(plot) || legends;
}

void layOutAt(QCustomPlot& plot, const FigureSize& size) {
    plot.resize(size.width_px, size.height_px);
    plot.setViewport(QRect(0, 0, size.width_px, size.height_px));
    plot.replot(QCustomPlot::rpImmediateRefresh);
    // A refit can move margins and so the panels' shapes again; a few rounds settle it.
    for (int round = 0; round < 3 && fitToLayout(plot); ++round)
        plot.replot(QCustomPlot::rpImmediateRefresh);
}

QString figuresDirectory(const QString& outDir) {
    const QString dir = outDir + "/figures";
    if (!QDir().mkpath(dir))
        throw std::runtime_error("cannot create " + dir.toStdString() +
                                 "; check the output folder is writable");
    return dir;
}

QStringList exportFigure(QCustomPlot& plot, const QString& basePath, const QStringList& formats,
                         const FigureSize& size) {
    QStringList written;
    // Lay out once at the target size so that every format sees the same geometry.
    layOutAt(plot, size);
    for (const QString& format : formats) {
        const QString file = basePath + "." + format.toLower();
        bool ok = false;
        if (format.compare("png", Qt::CaseInsensitive) == 0) {
            ok = plot.savePng(file, size.width_px, size.height_px, 1.0, -1, size.dpi,
                              QCP::ruDotsPerInch);
        } else if (format.compare("pdf", Qt::CaseInsensitive) == 0) {
            ok = plot.savePdf(file, size.width_px, size.height_px, QCP::epNoCosmetic,
                              "ActiveTouch Workbench", QFileInfo(basePath).baseName());
        } else if (format.compare("svg", Qt::CaseInsensitive) == 0) {
            QSvgGenerator svg;
            svg.setFileName(file);
            svg.setSize(QSize(size.width_px, size.height_px));
            svg.setViewBox(QRect(0, 0, size.width_px, size.height_px));
            svg.setTitle(QFileInfo(basePath).baseName());
            svg.setResolution(size.dpi);
            QCPPainter painter;
            ok = painter.begin(&svg);
            if (ok) {
                plot.toPainter(&painter, size.width_px, size.height_px);
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

}  // namespace activetouch
