#include "app/figures/FigureLayout.h"

#include <algorithm>

#include "qcustomplot.h"

namespace activetouch {

namespace {
/// The property of a legend under a panel holding the most entries a line may take.
constexpr const char* kMostPerLine = "mostEntriesPerLine";
}  // namespace

void startFigure(QCustomPlot& plot, const QString& title, const QString& caption) {
    plot.clearPlottables();
    plot.clearItems();
    plot.plotLayout()->clear();
    plot.setBackground(Qt::white);
    plot.setAutoAddPlottableToLegend(false);
    plot.plotLayout()->addElement(0, 0,
                                  new QCPTextElement(&plot, title, QFont("Sans", 12, QFont::Bold)));
    plot.plotLayout()->setRowStretchFactor(0, 0.001);
    if (caption.isEmpty()) return;
    // The figure's figures (counts, rates, errors) go under it, as a caption does.
    auto* text = new QCPTextElement(&plot, caption, QFont("Sans", 10));
    text->setObjectName("caption");
    text->setTextFlags(Qt::AlignLeft);
    plot.plotLayout()->addElement(1, 0, text);
    plot.plotLayout()->setRowStretchFactor(1, 0.001);
}

QCPLayoutGrid* addFigureRow(QCustomPlot& plot, double stretch) {
    auto* grid = new QCPLayoutGrid;
    QCPLayoutGrid* layout = plot.plotLayout();
    int row = layout->rowCount();
    // Rows go above a caption, which stays last.
    if (row > 1 && layout->element(row - 1, 0) &&
        layout->element(row - 1, 0)->objectName() == "caption") {
        layout->insertRow(row - 1);
        --row;
    }
    layout->addElement(row, 0, grid);
    layout->setRowStretchFactor(row, stretch);
    return grid;
}

QCPCurve* addPolyline(QCPAxis* xAxis, QCPAxis* yAxis, const std::vector<Vec2>& points,
                      bool closed) {
    auto* c = new QCPCurve(xAxis, yAxis);
    QVector<double> t, x, y;
    for (std::size_t i = 0; i < points.size(); ++i) {
        t << double(i);
        x << points[i].x;
        y << points[i].y;
    }
    if (closed && !points.empty()) {
        t << double(points.size());
        x << points.front().x;
        y << points.front().y;
    }
    c->setData(t, x, y);
    return c;
}

void integerTicks(QCPAxis* axis, double step) {
    QSharedPointer<QCPAxisTickerFixed> t(new QCPAxisTickerFixed);
    t->setTickStep(step);
    t->setScaleStrategy(QCPAxisTickerFixed::ssNone);
    axis->setTicker(t);
}

void setPanelTitle(QCPAxisRect* rect, const QString& text) {
    QCPAxis* top = rect->axis(QCPAxis::atTop);
    top->setVisible(true);
    top->setTicks(false);
    top->setTickLabels(false);
    top->setLabel(text);
}

QCPColorGradient heatGradient() {
    QCPColorGradient gradient(QCPColorGradient::gpThermal);
    gradient.setColorStopAt(1.0, QColor(255, 225, 40));
    return gradient;
}

QColor taxelColour(int k) {
    static const QColor palette[] = {
        QColor(0, 114, 178),   QColor(230, 159, 0),   QColor(0, 158, 115), QColor(204, 121, 167),
        QColor(86, 180, 233),  QColor(213, 94, 0),    QColor(0, 0, 0),     QColor(240, 228, 66),
        QColor(127, 127, 127), QColor(148, 103, 189), QColor(140, 86, 75), QColor(23, 190, 207)};
    return palette[((k % 12) + 12) % 12];
}

QColor seriesColour(int i) {
    static const QColor palette[] = {
        QColor(31, 119, 180),  QColor(255, 127, 14), QColor(44, 160, 44),   QColor(214, 39, 40),
        QColor(148, 103, 189), QColor(140, 86, 75),  QColor(227, 119, 194), QColor(127, 127, 127)};
    return palette[i % 8];
}

namespace {

void titleAndLabel(QCPAxisRect* rect, const QString& title, const QString& xLabel,
                   const QString& yLabel) {
    setPanelTitle(rect, title);
    rect->axis(QCPAxis::atBottom)->setLabel(xLabel);
    rect->axis(QCPAxis::atLeft)->setLabel(yLabel);
}

}  // namespace

QCPAxisRect* addTitledPanel(QCPLayoutGrid* grid, int column, const QString& title,
                            const QString& xLabel, const QString& yLabel) {
    auto* rect = new QCPAxisRect(grid->parentPlot());
    grid->addElement(0, column, rect);
    titleAndLabel(rect, title, xLabel, yLabel);
    return rect;
}

QCPLegend* addLegend(QCPAxisRect* rect) {
    auto* legend = new QCPLegend;
    rect->insetLayout()->addElement(legend, Qt::AlignTop | Qt::AlignRight);
    legend->setLayer("legend");
    legend->setFont(QFont("Sans", 8));
    legend->setBrush(QColor(255, 255, 255, 220));
    return legend;
}

PanelWithLegend addPanelWithLegendBelow(QCPLayoutGrid* grid, int row, int column, int perLine) {
    auto* cell = new QCPLayoutGrid;
    grid->addElement(row, column, cell);
    auto* rect = new QCPAxisRect(grid->parentPlot());
    cell->addElement(0, 0, rect);
    auto* legend = new QCPLegend;
    cell->addElement(1, 0, legend);
    cell->setRowStretchFactor(1, 0.001);
    legend->setLayer("legend");
    legend->setFont(QFont("Sans", 8));
    legend->setFillOrder(QCPLayoutGrid::foColumnsFirst);
    legend->setWrap(perLine);
    legend->setProperty(kMostPerLine, perLine);
    legend->setMargins(QMargins(4, 1, 4, 1));
    // The legend spans its cell, out to the figure's edge, where a frame would be cut off.
    legend->setBorderPen(Qt::NoPen);
    return {rect, legend};
}

QCPLegend* addLegendRow(QCustomPlot& plot, int perLine) {
    auto* legend = new QCPLegend;
    addFigureRow(plot, 0.001)->addElement(0, 0, legend);
    legend->setLayer("legend");
    legend->setFillOrder(QCPLayoutGrid::foColumnsFirst);
    legend->setWrap(perLine);
    legend->setProperty(kMostPerLine, perLine);
    return legend;
}

PanelWithLegend addTitledPanelWithLegendBelow(QCPLayoutGrid* grid, int row, int column, int perLine,
                                              const QString& title, const QString& xLabel,
                                              const QString& yLabel) {
    const PanelWithLegend panel = addPanelWithLegendBelow(grid, row, column, perLine);
    titleAndLabel(panel.rect, title, xLabel, yLabel);
    return panel;
}

namespace {

/// The width `e` gets from the layouts holding it when their columns share out the figure's
/// width by their stretch factors.
double shareOfWidth(const QCPLayoutElement* e, const QCustomPlot& plot) {
    const auto* grid = qobject_cast<const QCPLayoutGrid*>(e->layout());
    if (!grid) return plot.viewport().width();
    const double outer =
        grid == plot.plotLayout() ? plot.viewport().width() : shareOfWidth(grid, plot);
    const double inner = outer - grid->margins().left() - grid->margins().right() -
                         grid->columnSpacing() * (grid->columnCount() - 1);
    int column = 0;
    for (int i = 0; i < grid->elementCount(); ++i) {
        if (grid->elementAt(i) != e) continue;
        int row = 0;
        grid->indexToRowCol(i, row, column);
        break;
    }
    const QList<double> stretch = grid->columnStretchFactors();
    double total = 0.0;
    for (double f : stretch) total += f;
    return total > 0.0 ? inner * stretch.value(column) / total : inner;
}

/// The legend's entries in order (a legend's grid also counts the empty cells of its last line).
QList<const QCPAbstractLegendItem*> entriesOf(const QCPLegend* legend) {
    QList<const QCPAbstractLegendItem*> entries;
    for (int i = 0; i < legend->itemCount(); ++i)
        if (const QCPAbstractLegendItem* item = legend->item(i)) entries << item;
    return entries;
}

/// The width `entries` need with `perLine` of them to a line, filled line by line.
double legendWidth(const QCPLegend* legend, const QList<const QCPAbstractLegendItem*>& entries,
                   int perLine) {
    QList<double> columns(perLine, 0.0);
    for (int i = 0; i < entries.size(); ++i)
        columns[i % perLine] =
            std::max(columns[i % perLine], double(entries[i]->minimumOuterSizeHint().width()));
    double width = legend->margins().left() + legend->margins().right() +
                   legend->columnSpacing() * (perLine - 1);
    for (double c : columns) width += c;
    return width;
}

}  // namespace

bool fitLegendLines(QCustomPlot& plot) {
    bool changed = false;
    for (QCPLayoutElement* e : plot.plotLayout()->elements(true)) {
        auto* legend = qobject_cast<QCPLegend*>(e);
        if (!legend || !legend->property(kMostPerLine).isValid()) continue;
        const auto entries = entriesOf(legend);
        const int n = static_cast<int>(entries.size());
        if (n == 0) continue;
        const int asked = legend->property(kMostPerLine).toInt();
        int perLine = asked > 0 ? std::min(asked, n) : n;
        const double available = shareOfWidth(legend, plot);
        while (perLine > 1 && legendWidth(legend, entries, perLine) > available) --perLine;
        // Wrap 0 and any wrap of n or more put all n entries on one line.
        const int now = legend->wrap() > 0 ? std::min(legend->wrap(), n) : n;
        if (perLine == now) continue;
        legend->setWrap(perLine);
        legend->setFillOrder(QCPLayoutGrid::foColumnsFirst, true);
        changed = true;
    }
    return changed;
}

QCPGraph* addSeries(QCPAxisRect* rect, QCPLegend* legend, const QString& name,
                    const QVector<double>& x, const QVector<double>& y, QColor colour, bool lines) {
    auto* g =
        rect->parentPlot()->addGraph(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    g->setData(x, y);
    g->setName(name);
    g->setPen(lines ? QPen(colour, 1.8) : QPen(Qt::NoPen));
    g->setLineStyle(lines ? QCPGraph::lsLine : QCPGraph::lsNone);
    g->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, colour, colour, 6));
    if (legend) legend->addItem(new QCPPlottableLegendItem(legend, g));
    return g;
}

void addRunningBand(QCPAxisRect* rect, QCPLegend* legend, const QString& name,
                    const RunningValue& r, QColor colour) {
    if (r.x.isEmpty()) return;
    QColor fill = colour;
    fill.setAlpha(40);
    QCPGraph* low = addSeries(rect, nullptr, name + " (95 % low)", r.x, r.low, colour);
    QCPGraph* high = addSeries(rect, nullptr, name + " (95 % high)", r.x, r.high, colour);
    for (QCPGraph* g : {low, high}) {
        g->setPen(Qt::NoPen);
        g->setScatterStyle(QCPScatterStyle::ssNone);
    }
    high->setBrush(fill);
    high->setChannelFillGraph(low);
    QCPGraph* line = addSeries(rect, legend, name, r.x, r.value, colour);
    line->setScatterStyle(r.x.size() > 30 ? QCPScatterStyle(QCPScatterStyle::ssNone)
                                          : QCPScatterStyle(QCPScatterStyle::ssCircle, 5));
}

}  // namespace activetouch
