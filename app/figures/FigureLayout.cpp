#include "app/figures/FigureLayout.h"

#include "qcustomplot.h"

namespace activetouch {

void startFigure(QCustomPlot& plot, const QString& title) {
    plot.clearPlottables();
    plot.clearItems();
    plot.plotLayout()->clear();
    plot.setBackground(Qt::white);
    plot.setAutoAddPlottableToLegend(false);
    plot.plotLayout()->addElement(0, 0,
                                  new QCPTextElement(&plot, title, QFont("Sans", 12, QFont::Bold)));
    plot.plotLayout()->setRowStretchFactor(0, 0.001);
}

QCPLayoutGrid* addFigureRow(QCustomPlot& plot, double stretch) {
    auto* grid = new QCPLayoutGrid;
    const int row = plot.plotLayout()->rowCount();
    plot.plotLayout()->addElement(row, 0, grid);
    plot.plotLayout()->setRowStretchFactor(row, stretch);
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

QColor seriesColour(int i) {
    static const QColor palette[] = {
        QColor(31, 119, 180),  QColor(255, 127, 14), QColor(44, 160, 44),   QColor(214, 39, 40),
        QColor(148, 103, 189), QColor(140, 86, 75),  QColor(227, 119, 194), QColor(127, 127, 127)};
    return palette[i % 8];
}

QCPAxisRect* addTitledPanel(QCPLayoutGrid* grid, int column, const QString& title,
                            const QString& xLabel, const QString& yLabel) {
    auto* rect = new QCPAxisRect(grid->parentPlot());
    grid->addElement(0, column, rect);
    setPanelTitle(rect, title);
    rect->axis(QCPAxis::atBottom)->setLabel(xLabel);
    rect->axis(QCPAxis::atLeft)->setLabel(yLabel);
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
    legend->setMargins(QMargins(4, 1, 4, 1));
    // The legend spans its cell, out to the figure's edge, where a frame would be cut off.
    legend->setBorderPen(Qt::NoPen);
    return {rect, legend};
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

}  // namespace activetouch
