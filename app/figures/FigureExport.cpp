#include "app/figures/FigureExport.h"

#include <QFileInfo>
#include <QSvgGenerator>
#include <stdexcept>

#include "qcustomplot.h"

namespace activetouch {

void applyEqualAspect(QCustomPlot& plot) {
    bool changed = false;
    for (QCPAxisRect* rect : plot.axisRects()) {
        if (!rect->property("equalAspect").toBool()) continue;
        QCPAxis* x = rect->axis(QCPAxis::atBottom);
        QCPAxis* y = rect->axis(QCPAxis::atLeft);
        if (rect->width() <= 0 || rect->height() <= 0) continue;
        // Keep both data ranges visible: scale the axis that would otherwise be stretched.
        const double xPerPixel = x->range().size() / rect->width();
        const double yPerPixel = y->range().size() / rect->height();
        if (xPerPixel >= yPerPixel)
            y->setScaleRatio(x, 1.0);
        else
            x->setScaleRatio(y, 1.0);
        changed = true;
    }
    if (changed) plot.replot(QCustomPlot::rpImmediateRefresh);
}

QStringList exportFigure(QCustomPlot& plot, const QString& basePath, const QStringList& formats,
                         const FigureSize& size) {
    QStringList written;
    // Lay out once at the target size so that every format sees the same geometry.
    plot.resize(size.width_px, size.height_px);
    plot.replot(QCustomPlot::rpImmediateRefresh);
    applyEqualAspect(plot);
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
