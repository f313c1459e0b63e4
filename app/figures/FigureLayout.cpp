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

}  // namespace activetouch
