#pragma once
// Writing a plot to PNG, PDF and SVG at a given size and resolution. The same code serves the
// GUI's export actions and the headless runner.
#include <QString>
#include <QStringList>

class QCustomPlot;

namespace activetouch {

struct FigureSize {
    int width_px = 1600;
    int height_px = 1000;
    int dpi = 150;
};

/// Gives every axis rect marked with the property "equalAspect" one millimetre per pixel on both
/// axes (widening the range of the axis with room to spare). Call after the plot has its size.
void applyEqualAspect(QCustomPlot& plot);

/// Saves `plot` as `<basePath>.<format>` for each format in `formats` (png, pdf, svg).
/// Returns the files written; throws std::runtime_error naming the file that could not be written.
QStringList exportFigure(QCustomPlot& plot, const QString& basePath, const QStringList& formats,
                         const FigureSize& size);

}  // namespace activetouch
