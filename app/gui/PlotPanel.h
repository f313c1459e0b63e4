#pragma once
// A plot as the workbench shows it: a QCustomPlot with a context menu to export it (PNG, PDF, SVG
// at a chosen size and DPI), copy it to the clipboard, or export the data behind it as CSV.
// Replots are coalesced: callers change data and call requestReplot(); a timer draws at most
// once per frame. While a plot has nothing to draw it says, over the empty axes, what fills it.
#include <QLabel>
#include <QTimer>
#include <QWidget>

#include "app/figures/FigureExport.h"

class QCustomPlot;

namespace activetouch {

class PlotPanel : public QWidget {
    Q_OBJECT
public:
    explicit PlotPanel(const QString& name, QWidget* parent = nullptr);

    QCustomPlot& plot() { return *plot_; }
    const QString& name() const { return name_; }

    /// What a person does to fill this plot, shown over it while it has no data.
    void setEmptyHint(const QString& text);
    QString emptyHint() const { return hint_->text(); }
    bool showsEmptyHint() const { return !hint_->isHidden(); }

    /// Marks the plot for redrawing at the next frame.
    void requestReplot();

    /// Writes the plot in each format as <basePath>.<format>. Throws std::runtime_error.
    QStringList exportTo(const QString& basePath, const QStringList& formats,
                         const FigureSize& size);
    /// Writes every plottable's data, long format: plottable,name,x,y,value.
    void exportCsv(const QString& path) const;
    void copyToClipboard();

signals:
    void exported(const QString& what);
    void failed(const QString& message);

private:
    void showMenu(const QPoint& where);
    void exportWithDialog();
    void updateEmptyHint();
    /// True while the plot has nothing drawn and a hint says what fills it.
    bool waitsForData() const;
    QString name_;
    QCustomPlot* plot_;
    QLabel* hint_;
    QTimer replotTimer_;
    bool dirty_ = false;
    int refits_ = 0;  ///< equal-aspect refits in a row
};

}  // namespace activetouch
