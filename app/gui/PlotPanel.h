#pragma once
// A plot as the workbench shows it: a QCustomPlot to explore (wheel zoom, drag pan, double-click
// reset, the value under the cursor traced) with a context menu to export it (PNG, PDF, SVG at a
// physical size and DPI, journal presets), copy it to the clipboard, or export the data behind it
// as CSV with named columns and units.
// Replots are coalesced: callers change data and call requestReplot(); a timer draws at most
// once per frame. While a plot has nothing to draw it says, over the empty axes, what fills it.
#include <QLabel>
#include <QPointer>
#include <QTimer>
#include <QWidget>
#include <functional>

#include "app/figures/FigureExport.h"

class QCustomPlot;
class QCPAbstractPlottable;
class QCPItemTracer;
class QCPItemText;
class QCPRange;
class QCPAxis;

namespace activetouch {

class PlotPanel : public QWidget {
    Q_OBJECT
public:
    explicit PlotPanel(const QString& name, QWidget* parent = nullptr);

    QCustomPlot& plot() { return *plot_; }
    /// Where the export dialogs start: the window's results folder (docs/window.md), shared by
    /// every plot; empty leaves them in the working folder.
    static void setExportFolder(const QString& folder);
    /// The file an export dialog offers first: this plot's name with `extension`, in the export
    /// folder.
    QString suggestedPath(const QString& extension) const;
    const QString& name() const { return name_; }

    /// What a person does to fill this plot, shown over it while it has no data.
    void setEmptyHint(const QString& text);
    QString emptyHint() const { return hint_->text(); }
    bool showsEmptyHint() const { return !hint_->isHidden(); }

    /// Marks the plot for redrawing at the next frame.
    void requestReplot();

    /// How to draw the figure again, for a figure that lays itself out for the plot's shape: an
    /// export at another shape draws it for that shape, then again for the screen.
    void setRebuild(std::function<void(QCustomPlot&)> rebuild) { rebuild_ = std::move(rebuild); }

    /// Writes the plot in each format as <basePath>.<format>. Throws std::runtime_error.
    QStringList exportTo(const QString& basePath, const QStringList& formats,
                         const FigureSize& size);
    /// The height (mm) the figure is written at `widthMm` wide: its own (figureSizeFor, from its
    /// usual size as the command line writes it), whatever the window's shape. The plot on
    /// screen is left as it was.
    double ownHeightAt(double widthMm);
    /// Writes every plottable's data in long format, one row per point, each number beside its
    /// quantity and unit (taken from the axis labels): panel, series, then x, y and value (a
    /// colour map's cell) as name, unit and number.
    void exportCsv(const QString& path) const;

    /// Whether the person has zoomed or panned away from the plot's own ranges.
    bool isZoomed() const { return zoomed_; }
    /// Back to the plot's own ranges (a double-click).
    void resetView();
    /// Traces the point under `pos` (plot coordinates): the nearest graph point or curve or map
    /// cell within reach, else the axes' values there; returns what the label says.
    QString traceAt(const QPointF& pos);
    /// What the value label under the cursor says now (empty when hidden).
    QString cursorText() const;
    void copyToClipboard();

signals:
    void exported(const QString& what);
    void failed(const QString& message);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;
    /// A new palette (a dark desktop theme) redraws the plot in its ink.
    void changeEvent(QEvent* event) override;

private:
    /// Before the first zoom or pan: keeps the plot's own ranges for resetView().
    void rememberHome();
    void hideTracer();
    /// traceAt()'s parts: the tracer and its label made once; the plottable's point under the
    /// cursor, the tracer put on it, as text.
    void ensureTracer();
    QString describePoint(QCPAbstractPlottable* p, int index, const QPointF& pos);
    void showMenu(const QPoint& where);
    void exportWithDialog();
    /// Runs `work`, which lays the plot out for a page of its own, then puts the screen's layout
    /// back (also if `work` throws).
    void offScreen(const std::function<void()>& work);
    /// A figure that lays itself out for the plot's shape drawn again for `shape`.
    void drawnFor(QSize shape);
    /// The size the figure is written at by the command line (runFigures and the others).
    FigureSize usualSize() const;
    void updateEmptyHint();
    /// True while the plot has nothing drawn and a hint says what fills it.
    bool waitsForData() const;
    QString name_;
    QCustomPlot* plot_;
    QLabel* hint_;
    QTimer replotTimer_;
    bool dirty_ = false;
    bool zoomed_ = false;
    bool onPage_ = false;  ///< laid out for an export: light ink
    std::function<void(QCustomPlot&)> rebuild_;
    QList<QPair<QCPAxis*, QPair<double, double>>> home_;  ///< each axis's own range
    QPointer<QCPItemTracer> tracer_;  ///< the figure's code may clear the items: guarded
    QPointer<QCPItemText> cursorLabel_;
    const void* shownFigure_ = nullptr;  ///< the first plottable: a new one is a new figure
};

}  // namespace activetouch
