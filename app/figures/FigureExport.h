#pragma once
// Writing a plot to PNG, PDF and SVG at a given size and resolution. The same code serves the
// GUI's export actions and the headless runner.
#include <QSize>
#include <QString>
#include <QStringList>
#include <functional>

class QCustomPlot;
class QCPAxisRect;
class QCPLegend;
class QCPRange;

namespace activetouch {

/// The size a figure is written at: pixels (a screen figure), or a physical size in mm with a
/// resolution (a journal figure: laid out at that size with its text at 7-9 pt; a PNG gets
/// width_mm / 25.4 * dpi pixels, a PDF or SVG the size itself).
struct FigureSize {
    int width_px = 1600;
    int height_px = 1000;
    int dpi = 150;
    double width_mm = 0.0;  ///< > 0 with height_mm: a physical size
    double height_mm = 0.0;

    static constexpr FigureSize physical(double widthMm, double heightMm, int dpi) {
        return {static_cast<int>(widthMm / 25.4 * dpi + 0.5),
                static_cast<int>(heightMm / 25.4 * dpi + 0.5), dpi, widthMm, heightMm};
    }
    constexpr bool isPhysical() const { return width_mm > 0.0 && height_mm > 0.0; }
};

/// Journal widths: a single column and a whole page (double column), mm.
inline constexpr double kSingleColumn_mm = 89.0;
inline constexpr double kDoubleColumn_mm = 178.0;
/// The size the figure built in `plot` is written at `widthMm` wide: `usual`'s height (its
/// height at its usual width) times how much taller its rows of panels grow at that width as
/// they wrap (reflowPanels), at `usual`'s resolution; never a window's shape. Leaves the plot
/// laid out at that width.
FigureSize figureSizeFor(QCustomPlot& plot, const FigureSize& usual, double widthMm);

/// The resolution figures are written at unless asked otherwise: a journal's for line art with
/// grey levels.
inline constexpr int kFigureDpi = 300;
/// The smallest and largest text of a physical figure, points.
inline constexpr double kSmallestText_pt = 7.0;
inline constexpr double kLargestText_pt = 9.0;

/// Scales every text of `plot` (titles, axis and tick labels, legends, colour scales, text
/// items) so that the largest is kLargestText_pt and none is under kSmallestText_pt, keeping
/// their order of size. Returns a function that puts the fonts back as they were.
std::function<void()> setJournalText(QCustomPlot& plot);

/// Shows `x` and `y` in `rect` at one unit per pixel on both axes from then on: fitEqualAspect
/// widens one of these ranges to fit the rect's shape, always starting again from them.
void setEqualAspectRanges(QCPAxisRect* rect, const QCPRange& x, const QCPRange& y);

/// The legend in `rect`'s top right corner stays clear of the data, which reaches up to `dataTop`
/// and right to `dataRight`: where the panel's shape leaves it no room beside the data,
/// fitEqualAspect raises the top of the view until the legend fits above it.
void keepLegendClear(QCPAxisRect* rect, QCPLegend* legend, double dataRight, double dataTop);

/// Gives every axis rect set up by setEqualAspectRanges equal scales on both axes for its current
/// size, widening the axis with room to spare from the ranges asked for (so repeated resizes never
/// accumulate). Returns whether any range changed; does not replot. Call after a layout.
bool fitEqualAspect(QCustomPlot& plot);

/// How many layouts a refit may take to settle: wrapping panels or labels moves the margins, and
/// so the panels' shapes, again.
inline constexpr int kLayoutRounds = 8;

/// Refits what depends on the plot's size after a layout: the lines of the legends under panels
/// (fitLegendLines) and the equal-aspect ranges. Returns whether anything changed, and so whether
/// the plot needs laying out again; does not replot.
bool fitToLayout(QCustomPlot& plot);

/// Lays `plot` out at `size` as it is written: its viewport at that size (a plot that is not shown
/// gets no resize event, so resizing it alone leaves the layout at its old size) and its
/// equal-aspect panels fitted to their shapes there. A physical size is laid out at its size in
/// the plot's logical pixels, with journal text (setJournalText; left so).
void layOutAt(QCustomPlot& plot, const FigureSize& size);

/// The size `plot` is laid out at for `size`: its pixels, or a physical size in the plot's
/// logical pixels. A figure that lays itself out for the plot's shape is built at this size.
QSize layoutSize(const QCustomPlot& plot, const FigureSize& size);

/// <outDir>/figures, made if need be; throws std::runtime_error naming it if it cannot be.
QString figuresDirectory(const QString& outDir);

/// Saves `plot` as `<basePath>.<format>` for each format in `formats` (png, pdf, svg).
/// Returns the files written; throws std::runtime_error naming the file that could not be written.
QStringList exportFigure(QCustomPlot& plot, const QString& basePath, const QStringList& formats,
                         const FigureSize& size);

}  // namespace activetouch
