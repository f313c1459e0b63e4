#include "app/figures/SweepFigures.h"

#include <cmath>
#include <map>
#include <tuple>

#include "app/figures/FigureLayout.h"
#include "core/run/ExperimentRun.h"
#include "qcustomplot.h"

namespace activetouch {
namespace {

void markPaper(QCPAxisRect* rect, QCPLegend* legend, double x, double y, const QString& what) {
    auto* g = addSeries(rect, legend, what, {x}, {y}, Qt::black, false);
    g->setScatterStyle(
        QCPScatterStyle(QCPScatterStyle::ssStar, QPen(Qt::black, 2), Qt::NoBrush, 14));
}

void pointLabel(QCPAxisRect* rect, double x, double y, const QString& text) {
    auto* label = new QCPItemText(rect->parentPlot());
    label->setClipAxisRect(rect);
    label->position->setAxes(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    label->position->setCoords(x, y);
    label->setPositionAlignment(Qt::AlignBottom | Qt::AlignLeft);
    label->setFont(QFont("Sans", 7));
    label->setText(text);
}

void fit(QCPAxisRect* rect) {
    bool found = false;
    QCPRange x, y;
    for (QCPAbstractPlottable* g : rect->plottables()) {  // graphs and their error bars
        bool ok = false;
        const QCPRange gx = g->getKeyRange(ok);
        if (!ok) continue;
        const QCPRange gy = g->getValueRange(ok);
        x = found ? QCPRange(std::min(x.lower, gx.lower), std::max(x.upper, gx.upper)) : gx;
        y = found ? QCPRange(std::min(y.lower, gy.lower), std::max(y.upper, gy.upper)) : gy;
        found = true;
    }
    if (!found) return;
    const double dx = std::max(1e-6, x.size()) * 0.08, dy = std::max(1e-6, y.size()) * 0.1;
    rect->axis(QCPAxis::atBottom)->setRange(x.lower - dx, x.upper + dx);
    rect->axis(QCPAxis::atLeft)->setRange(std::max(0.0, y.lower - dy), y.upper + 3 * dy);
    // Labels at points in the right half read leftwards, so that none runs off the panel.
    const double middle = rect->axis(QCPAxis::atBottom)->range().center();
    QCustomPlot* plot = rect->parentPlot();
    for (int i = 0; i < plot->itemCount(); ++i)
        if (auto* label = qobject_cast<QCPItemText*>(plot->item(i));
            label && label->clipAxisRect() == rect && label->position->coords().x() > middle)
            label->setPositionAlignment(Qt::AlignBottom | Qt::AlignRight);
}

}  // namespace

bool buildPerceptionSweepFigure(QCustomPlot& plot, const RunResult& r) {
    const auto& rows = r.sweeps.perception;
    startFigure(plot,
                "Accuracy costs time (a): sequential perception, error against taps per decision");
    if (rows.empty()) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    QVector<double> taps, angle, position, angleBelow, angleAbove, positionBelow, positionAbove;
    for (const auto& row : rows) {
        taps << row.meanTaps;
        angle << row.angleError_deg;
        position << row.positionError_mm;
        angleBelow << row.angleError_deg - row.angle_deg.low;
        angleAbove << row.angle_deg.high - row.angleError_deg;
        positionBelow << row.positionError_mm - row.position_mm.low;
        positionAbove << row.position_mm.high - row.positionError_mm;
    }
    auto* a = addTitledPanel(grid, 0, "edge angle error (edge classes)", "mean taps per decision",
                             "angle error (°)");
    auto* p =
        addTitledPanel(grid, 1, "position error", "mean taps per decision", "position error (mm)");
    auto* la = addLegend(a);
    auto* lp = addLegend(p);
    const QString name = r.sweeps.perceptionCalibration.calibrated
                             ? "belief thresholds (calibrated belief), 95 % intervals"
                             : "belief thresholds, 95 % intervals";
    auto bars = [](QCPGraph* g, const QVector<double>& below, const QVector<double>& above) {
        auto* e = new QCPErrorBars(g->keyAxis(), g->valueAxis());
        e->setDataPlottable(g);
        e->setData(below, above);
        e->setPen(g->pen());
        e->removeFromLegend();
    };
    QVariantList all;
    for (int i = 0; i < int(rows.size()); ++i) all << i;
    for (auto [rect, legend, y, below, above] :
         {std::tuple{a, la, &angle, &angleBelow, &angleAbove},
          std::tuple{p, lp, &position, &positionBelow, &positionAbove}}) {
        QCPGraph* g = addSeries(rect, legend, name, taps, *y, seriesColour(0));
        g->setProperty(kSweepRowsProperty, all);
        bars(g, *below, *above);
    }
    const PerceptionSweepRow& one = r.sweeps.perceptionSingleTap;
    markPaper(a, la, one.meanTaps, one.angleError_deg, "paper: single tap (same taps)");
    markPaper(p, lp, one.meanTaps, one.positionError_mm, "paper: single tap (same taps)");
    for (std::size_t i = 0; i < rows.size(); ++i) {
        pointLabel(a, taps[int(i)], angle[int(i)], QString::number(rows[i].threshold, 'g', 12));
        pointLabel(p, taps[int(i)], position[int(i)], QString::number(rows[i].threshold, 'g', 12));
    }
    fit(a);
    fit(p);
    return true;
}

bool buildFollowingSweepFigure(QCustomPlot& plot, const RunResult& r) {
    const auto& rows = r.sweeps.following;
    startFigure(
        plot,
        "Accuracy costs time (b): contour following against step lengths and belief threshold");
    if (rows.empty()) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    // Completion may sit anywhere from 0 to 100 %: these legends go under their panels.
    const auto [completion, lc] = addPanelWithLegendBelow(grid, 0, 0, /*perLine=*/1);
    setPanelTitle(completion, "completion (single-tap decisions)");
    completion->axis(QCPAxis::atBottom)->setLabel("follow step (mm)");
    completion->axis(QCPAxis::atLeft)->setLabel("trials completed (%)");
    const auto [time, lt] = addPanelWithLegendBelow(grid, 0, 1, /*perLine=*/1);
    setPanelTitle(time, "robot time (single-tap decisions)");
    time->axis(QCPAxis::atBottom)->setLabel("follow step (mm)");
    time->axis(QCPAxis::atLeft)->setLabel("robot time per completion (s)");
    const auto [trade, lx] = addPanelWithLegendBelow(grid, 0, 2, /*perLine=*/1);
    setPanelTitle(trade, "time against path error");
    trade->axis(QCPAxis::atBottom)->setLabel("mean distance of taps to the contour (mm)");
    trade->axis(QCPAxis::atLeft)->setLabel("robot time per completion (s)");
    struct Line {
        QVector<double> x, completion, time;
        QVariantList rows;
    };
    std::map<std::pair<int, double>, Line> lines;
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const auto& row = rows[r];
        if (row.beliefThreshold != 0.0) continue;
        auto& l = lines[{int(row.mode), row.repositionStep_mm}];
        l.rows << int(r);
        l.x << row.followStep_mm;
        l.completion << 100.0 * row.completed / row.trials;
        l.time << (std::isfinite(row.robotTimePerCompletion_s) ? row.robotTimePerCompletion_s
                                                               : qQNaN());
    }
    int i = 0;
    for (const auto& [key, l] : lines) {
        const QString name = key.first == int(FollowingMode::Active)
                                 ? QString("active, reposition %1 mm").arg(key.second)
                                 : QString("passive");
        addSeries(completion, lc, name, l.x, l.completion, seriesColour(i))
            ->setProperty(kSweepRowsProperty, l.rows);
        addSeries(time, lt, name, l.x, l.time, seriesColour(i))
            ->setProperty(kSweepRowsProperty, l.rows);
        ++i;
    }
    std::map<double, Line> byThreshold;
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const auto& row = rows[r];
        if (row.mode != FollowingMode::Active || !std::isfinite(row.robotTimePerCompletion_s))
            continue;
        byThreshold[row.beliefThreshold].x << row.meanContourDistance_mm;
        byThreshold[row.beliefThreshold].time << row.robotTimePerCompletion_s;
        byThreshold[row.beliefThreshold].rows << int(r);
    }
    i = 0;
    for (const auto& [threshold, pts] : byThreshold)
        addSeries(trade, lx,
                  threshold == 0.0 ? QString("single tap")
                                   : QString("belief threshold %1").arg(threshold, 0, 'g', 12),
                  pts.x, pts.time, seriesColour(i++), false)
            ->setProperty(kSweepRowsProperty, pts.rows);
    for (const auto& row : rows)
        if (row.paperSetting && row.mode == FollowingMode::Active) {
            markPaper(completion, lc, row.followStep_mm, 100.0 * row.completed / row.trials,
                      "paper: 2 mm, 1 mm, single tap");
            if (std::isfinite(row.robotTimePerCompletion_s)) {
                markPaper(time, lt, row.followStep_mm, row.robotTimePerCompletion_s,
                          "paper: 2 mm, 1 mm, single tap");
                markPaper(trade, lx, row.meanContourDistance_mm, row.robotTimePerCompletion_s,
                          "paper: 2 mm, 1 mm, single tap");
            }
        }
    fit(completion);
    // Room above 100 % for the legend, but no share is ever labelled above 100 %.
    completion->axis(QCPAxis::atLeft)->setRange(0, 130);
    QSharedPointer<QCPAxisTickerText> percent(new QCPAxisTickerText);
    for (int v = 0; v <= 100; v += 25) percent->addTick(v, QString::number(v));
    completion->axis(QCPAxis::atLeft)->setTicker(percent);
    fit(time);
    fit(trade);
    return true;
}

bool buildComputeSweepFigure(QCustomPlot& plot, const RunResult& r) {
    const auto& rows = r.sweeps.compute;
    startFigure(plot,
                "Accuracy costs time (c): classifier error against microseconds per decision "
                "(labels: histogram bins)");
    if (rows.empty()) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    auto* a =
        addTitledPanel(grid, 0, "angle error", "microseconds per decision", "angle error (°)");
    auto* p = addTitledPanel(grid, 1, "position error", "microseconds per decision",
                             "position error (mm)");
    auto* la = addLegend(a);
    auto* lp = addLegend(p);
    std::map<int, std::vector<const ComputeSweepRow*>> bySamples;
    for (const auto& row : rows) bySamples[row.samples].push_back(&row);
    int i = 0;
    for (const auto& [samples, list] : bySamples) {
        QVector<double> us, angle, position;
        for (const auto* row : list) {
            us << row->microsecondsPerDecision;
            angle << row->angleError_deg;
            position << row->positionError_mm;
            pointLabel(a, row->microsecondsPerDecision, row->angleError_deg,
                       QString::number(row->bins));
            pointLabel(p, row->microsecondsPerDecision, row->positionError_mm,
                       QString::number(row->bins));
        }
        addSeries(a, la, QString("%1 samples per tap").arg(samples), us, angle, seriesColour(i));
        addSeries(p, lp, QString("%1 samples per tap").arg(samples), us, position, seriesColour(i));
        ++i;
    }
    for (const auto& row : rows)
        if (row.paperSetting) {
            markPaper(a, la, row.microsecondsPerDecision, row.angleError_deg,
                      "paper: 100 bins, 50 samples");
            markPaper(p, lp, row.microsecondsPerDecision, row.positionError_mm,
                      "paper: 100 bins, 50 samples");
        }
    fit(a);
    fit(p);
    return true;
}

}  // namespace activetouch
