#include "app/figures/ComparisonFigures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "app/figures/FigureLayout.h"
#include "app/run/PairedComparison.h"
#include "qcustomplot.h"

namespace activetouch {

bool buildComparisonFigure(QCustomPlot& plot, const PairedComparison& c) {
    const QString a = QString::fromStdString(c.nameA), b = QString::fromStdString(c.nameB);
    startFigure(plot, QString("%1 (B) against %2 (A), %3 seeds").arg(b, a).arg(c.seeds));
    struct Row {
        const char* name;
        const PairedRate* rate;
    };
    std::vector<Row> rows;
    for (const Row& r : {Row{"active trials completed", &c.activeCompleted},
                         Row{"passive trials lost at a corner", &c.passiveLostAtCorner},
                         Row{"completed paths recognised (paper's rule)", &c.recognisedRaw},
                         Row{"runs with the paper's result whole", &c.paperResult}})
        if (r.rate->pairs() > 0) rows.push_back(r);
    if (rows.empty()) return false;

    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    QCPAxisRect* rect = addTitledPanel(grid, 0,
                                       QString("robot time per run: A %1 min, B %2 min")
                                           .arg(std::lround(c.meanRobotTimeA_s() / 60.0))
                                           .arg(std::lround(c.meanRobotTimeB_s() / 60.0)),
                                       "B - A with 95 % interval (percentage points)", "");
    QCPAxis* x = rect->axis(QCPAxis::atBottom);
    QCPAxis* y = rect->axis(QCPAxis::atLeft);
    // The first outcome at the top.
    const int n = static_cast<int>(rows.size());
    QVector<double> key, value;
    QVector<double> minus, plus;
    QSharedPointer<QCPAxisTickerText> names(new QCPAxisTickerText);
    double lo = 0.0, hi = 0.0;
    // Keys ascending, as the graph and its error bars keep them: the last row first.
    for (int i = n - 1; i >= 0; --i) {
        const PairedRate& r = *rows[static_cast<std::size_t>(i)].rate;
        const double at = n - i, d = 100.0 * r.difference();
        const double low = 100.0 * r.differenceLow(), high = 100.0 * r.differenceHigh();
        key << at;
        value << d;
        minus << d - low;
        plus << high - d;
        lo = std::min(lo, low);
        hi = std::max(hi, high);
        // Under each part's name, its counts and McNemar's p.
        names->addTick(at, QString("%1\nA %2/%3, B %4/%5; only A %6, only B %7; p %8")
                               .arg(rows[static_cast<std::size_t>(i)].name)
                               .arg(r.a().count)
                               .arg(r.pairs())
                               .arg(r.b().count)
                               .arg(r.pairs())
                               .arg(r.onlyA)
                               .arg(r.onlyB)
                               .arg(r.mcnemarP(), 0, 'g', 2));
    }
    QCPGraph* points = plot.addGraph(y, x);  // keys up the side, values across
    points->setName("B - A");
    points->setData(key, value, true);
    points->setLineStyle(QCPGraph::lsNone);
    points->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssDisc, seriesColour(0), 8));
    auto* bars = new QCPErrorBars(y, x);
    bars->setName("95 % interval");
    bars->setDataPlottable(points);
    bars->setData(minus, plus);
    bars->setPen(QPen(seriesColour(0), 1.5));
    y->setTicker(names);
    y->setRange(0.4, n + 0.6);
    const double span = std::max(hi - lo, 2.0);
    x->setRange(lo - 0.08 * span, hi + 0.08 * span);
    auto* zero = new QCPItemStraightLine(&plot);
    zero->setClipAxisRect(rect);
    zero->point1->setAxes(x, y);
    zero->point2->setAxes(x, y);
    zero->point1->setCoords(0.0, 0.0);
    zero->point2->setCoords(0.0, 1.0);
    zero->setPen(QPen(Qt::gray, 1, Qt::DashLine));
    return true;
}

QStringList writeComparisonFigures(const PairedComparison& comparison, const QString& outDir) {
    const QString dir = figuresDirectory(outDir);
    QCustomPlot plot;
    if (!buildComparisonFigure(plot, comparison)) return {};
    return exportFigure(plot, dir + "/compare", {"png", "pdf", "svg"}, kComparisonFigureSize);
}

}  // namespace activetouch
