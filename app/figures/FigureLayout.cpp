#include "app/figures/FigureLayout.h"

#include "qcustomplot.h"

namespace activetouch {

void startFigure(QCustomPlot& plot, const QString& title) {
    plot.clearPlottables();
    plot.clearItems();
    plot.plotLayout()->clear();
    plot.setBackground(Qt::white);
    plot.setAutoAddPlottableToLegend(false);
    plot.plotLayout()->addElement(0, 0, new QCPTextElement(&plot, title, QFont("Sans", 12, QFont::Bold)));
    plot.plotLayout()->setRowStretchFactor(0, 0.001);
}

QCPLayoutGrid* addFigureRow(QCustomPlot& plot, double stretch) {
    auto* grid = new QCPLayoutGrid;
    const int row = plot.plotLayout()->rowCount();
    plot.plotLayout()->addElement(row, 0, grid);
    plot.plotLayout()->setRowStretchFactor(row, stretch);
    return grid;
}

void setPanelTitle(QCPAxisRect* rect, const QString& text) {
    QCPAxis* top = rect->axis(QCPAxis::atTop);
    top->setVisible(true);
    top->setTicks(false);
    top->setTickLabels(false);
    top->setLabel(text);
}

}  // namespace activetouch
