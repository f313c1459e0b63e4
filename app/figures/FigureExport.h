#pragma once
// Writing a plot to PNG, PDF and SVG at a given size and resolution. The same code serves the
// GUI's export actions and the headless runner.
#include <QString>
#include <QStringList>

class QCustomPlot;
class QCPAxisRect;
class QCPRange;

namespace activetouch {

struct FigureSize {
    int width_px = 1600;
    int height_px = 1000;
    int dpi = 150;
};

/// Shows `x` and `y` in `rect` at one unit per pixel on both axes from then on: fitEqualAspect
/// widens one of these ranges to fit the rect's shape, always starting again from them.
void setEqualAspectRanges(QCPAxisRect* rect, const QCPRange& x, const QCPRange& y);

/// Gives every axis rect set up by setEqualAspectRanges equal scales on both axes for its current
/// size, widening the axis with room to spare from the ranges asked for (so repeated resizes never
/// accumulate). Returns whether any range changed; does not replot. Call after a layout.
bool fitEqualAspect(QCustomPlot& plot);

/// Refits what depends on the plot's size after a layout: the lines of the legends under panels
/// (fitLegendLines) and the equal-aspect ranges. Returns whether anything changed, and so whether
/// the plot needs laying out again; does not replot.
bool fitToLayout(QCustomPlot& plot);

/// Lays `plot` out at `size` as it is written: its viewport at that size (a plot that is not shown
/// gets no resize event, so resizing it alone leaves the layout at its old size) and its
/// equal-aspect panels fitted to their shapes there.
void layOutAt(QCustomPlot& plot, const FigureSize& size);

/// <outDir>/figures, made if need be; throws std::runtime_error naming it if it cannot be.
QString figuresDirectory(const QString& outDir);

/// Saves `plot` as `<basePath>.<format>` for each format in `formats` (png, pdf, svg).
/// Returns the files written; throws std::runtime_error naming the file that could not be written.
QStringList exportFigure(QCustomPlot& plot, const QString& basePath, const QStringList& formats,
                         const FigureSize& size);

}  // namespace activetouch
