#include "app/figures/SweepFigures.h"

#include <cmath>
#include <map>
#include <tuple>

#include "app/figures/FigureLayout.h"
#include "app/figures/FigureReflow.h"
#include "core/analysis/SweepRates.h"
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
    markPointLabel(label);
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
    // The labels find their side of their points at the panel's size (placePointLabels).
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
    const auto [a, la] =
        addTitledPanelWithLegendBelow(grid, 0, 0, /*perLine=*/1, "edge angle error (edge classes)",
                                      "mean taps per decision", "angle error (°)");
    const auto [p, lp] =
        addTitledPanelWithLegendBelow(grid, 0, 1, /*perLine=*/1, "position error",
                                      "mean taps per decision", "position error (mm)");
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
    const auto [completion, lc] = addTitledPanelWithLegendBelow(
        grid, 0, 0, /*perLine=*/1, "completion (single-tap decisions)", "follow step (mm)",
        "trials completed (%)");
    const auto [time, lt] = addTitledPanelWithLegendBelow(
        grid, 0, 1, /*perLine=*/1, "robot time (single-tap decisions)", "follow step (mm)",
        "robot time per completion (s)");
    const auto [trade, lx] = addTitledPanelWithLegendBelow(
        grid, 0, 2, /*perLine=*/1, "time against path error",
        "mean distance of taps to the contour (mm)", "robot time per completion (s)");
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
    // Room above 100 % for the points drawn at it, but no share is ever labelled above 100 %.
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
    const auto [a, la] = addTitledPanelWithLegendBelow(
        grid, 0, 0, /*perLine=*/2, "angle error", "microseconds per decision", "angle error (°)");
    const auto [p, lp] =
        addTitledPanelWithLegendBelow(grid, 0, 1, /*perLine=*/2, "position error",
                                      "microseconds per decision", "position error (mm)");
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

namespace {

/// Error bars on `g`: values (and keys, if given) from their intervals.
void intervalBars(QCPGraph* g, const std::vector<SweepEstimate>& y,
                  const std::vector<SweepEstimate>* x = nullptr) {
    auto bars = [g](QCPErrorBars::ErrorType type, const std::vector<SweepEstimate>& e) {
        QVector<double> below, above;
        for (const SweepEstimate& v : e) {
            below << (std::isfinite(v.low) ? v.mean - v.low : 0.0);
            above << (std::isfinite(v.high) ? v.high - v.mean : 0.0);
        }
        auto* bar = new QCPErrorBars(g->keyAxis(), g->valueAxis());
        bar->setErrorType(type);
        bar->setDataPlottable(g);
        bar->setData(below, above);
        // A series drawn as points alone has no line pen: the bars take its points' colour.
        QPen pen = g->pen();
        if (pen.style() == Qt::NoPen) pen = QPen(g->scatterStyle().pen().color(), 1.5);
        bar->setPen(pen);
        bar->removeFromLegend();
    };
    bars(QCPErrorBars::etValueError, y);
    if (x) bars(QCPErrorBars::etKeyError, *x);
}

QString settingLabel(const FollowingOverSeeds& f) {
    const QString threshold =
        f.beliefThreshold > 0 ? QString(", %1").arg(f.beliefThreshold, 0, 'g', 6) : QString();
    return f.mode == FollowingMode::Active
               ? QString("%1/%2%3").arg(f.followStep_mm).arg(f.repositionStep_mm).arg(threshold)
               : QString("passive %1%2").arg(f.followStep_mm).arg(threshold);
}

}  // namespace

bool buildPerceptionSweepOverSeedsFigure(QCustomPlot& plot, const SweepRates& r) {
    startFigure(plot, QString("Accuracy costs time (a) over %1 seeds: sequential perception, "
                              "error against taps per decision")
                          .arg(r.seeds));
    if (r.perception.empty()) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    const auto [a, la] =
        addTitledPanelWithLegendBelow(grid, 0, 0, /*perLine=*/2, "edge angle error (edge classes)",
                                      "mean taps per decision", "angle error (°)");
    const auto [p, lp] =
        addTitledPanelWithLegendBelow(grid, 0, 1, /*perLine=*/2, "position error",
                                      "mean taps per decision", "position error (mm)");
    QVector<double> taps, angle, position;
    std::vector<SweepEstimate> tapsE, angleE, positionE;
    for (const auto& row : r.perception) {
        taps << row.taps.mean;
        angle << row.angle_deg.mean;
        position << row.position_mm.mean;
        tapsE.push_back(row.taps);
        angleE.push_back(row.angle_deg);
        positionE.push_back(row.position_mm);
    }
    const QString name = "belief thresholds, mean over seeds, 95 % intervals";
    intervalBars(addSeries(a, la, name, taps, angle, seriesColour(0)), angleE, &tapsE);
    intervalBars(addSeries(p, lp, name, taps, position, seriesColour(0)), positionE, &tapsE);
    const PerceptionOverSeeds& one = r.perceptionSingleTap;
    markPaper(a, la, one.taps.mean, one.angle_deg.mean, "paper: single tap (same taps)");
    markPaper(p, lp, one.taps.mean, one.position_mm.mean, "paper: single tap (same taps)");
    for (std::size_t i = 0; i < r.perception.size(); ++i) {
        const QString t = QString::number(r.perception[i].threshold, 'g', 12);
        pointLabel(a, taps[int(i)], angle[int(i)], t);
        pointLabel(p, taps[int(i)], position[int(i)], t);
    }
    fit(a);
    fit(p);
    return true;
}

namespace {

using Shown = std::vector<const FollowingOverSeeds*>;

/// Two panels of the following trade-off, each with its legend below.
struct ParetoPanels {
    QCPAxisRect *completion, *distance;
    QCPLegend *lc, *ld;
};

/// One series per mode and threshold, with their intervals both ways.
void addFollowingSeries(const ParetoPanels& p, const Shown& shown) {
    std::map<std::pair<int, double>, Shown> groups;
    for (const auto* f : shown) groups[{int(f->mode), f->beliefThreshold}].push_back(f);
    int colour = 0;
    for (const auto& [key, list] : groups) {
        QVector<double> t, c, d;
        std::vector<SweepEstimate> tE, cE, dE;
        for (const auto* f : list) {
            t << f->robotTimePerCompletion_s.mean;
            tE.push_back(f->robotTimePerCompletion_s);
            c << 100.0 * f->completed.fraction();
            cE.push_back({100.0 * f->completed.fraction(), 100.0 * f->completed.low(),
                          100.0 * f->completed.high()});
            d << f->contourDistance_mm.mean;
            dE.push_back(f->contourDistance_mm);
        }
        const QString name =
            QString("%1, %2")
                .arg(modeName(FollowingMode(key.first)))
                .arg(key.second > 0 ? QString("threshold %1").arg(key.second, 0, 'g', 6)
                                    : QString("single tap"));
        intervalBars(addSeries(p.completion, p.lc, name, t, c, seriesColour(colour), false), cE,
                     &tE);
        intervalBars(addSeries(p.distance, p.ld, name, t, d, seriesColour(colour), false), dE, &tE);
        ++colour;
    }
}

/// The Pareto front circled in order of time: a front in three measures, so no line joins it.
void addParetoFront(const ParetoPanels& p, const Shown& shown) {
    Shown front;
    for (const auto* f : shown)
        if (f->onParetoFront) front.push_back(f);
    std::sort(front.begin(), front.end(), [](const auto* a, const auto* b) {
        return a->robotTimePerCompletion_s.mean < b->robotTimePerCompletion_s.mean;
    });
    QVector<double> ft, fc, fd;
    for (const auto* f : front) {
        ft << f->robotTimePerCompletion_s.mean;
        fc << 100.0 * f->completed.fraction();
        fd << f->contourDistance_mm.mean;
    }
    for (auto [rect, legend, y] :
         {std::tuple{p.completion, p.lc, &fc}, std::tuple{p.distance, p.ld, &fd}}) {
        auto* g =
            addSeries(rect, legend, "Pareto front (time, completion, distance)", ft, *y, Qt::black);
        g->setScatterStyle(
            QCPScatterStyle(QCPScatterStyle::ssCircle, QPen(Qt::black, 1.5), Qt::NoBrush, 10));
        g->setLineStyle(QCPGraph::lsNone);
    }
}

/// The paper's setting marked; it and the settings that beat it named (only those, so that
/// labels do not pile up; the front is circled, and named in the tables).
void labelPaperAndWinners(const ParetoPanels& p, const Shown& shown) {
    for (const auto* f : shown) {
        const bool paper = f->paperSetting && f->mode == FollowingMode::Active;
        const double t = f->robotTimePerCompletion_s.mean, c = 100.0 * f->completed.fraction();
        if (paper) {
            markPaper(p.completion, p.lc, t, c, "paper: 2 mm, 1 mm, single tap");
            markPaper(p.distance, p.ld, t, f->contourDistance_mm.mean,
                      "paper: 2 mm, 1 mm, single tap");
        }
        if (!f->beatsPaper && !paper) continue;
        const QString label = settingLabel(*f) + (f->beatsPaper ? " (beats paper)" : "");
        pointLabel(p.completion, t, c, label);
        pointLabel(p.distance, t, f->contourDistance_mm.mean, label);
    }
}

/// Robot time on a logarithmic axis: widened by factors, not by steps, its lower end positive.
void logTimeAxis(QCPAxisRect* rect, const Shown& shown) {
    QCPAxis* x = rect->axis(QCPAxis::atBottom);
    x->setScaleType(QCPAxis::stLogarithmic);
    QSharedPointer<QCPAxisTickerText> ticks(new QCPAxisTickerText);
    for (double decade = 1e-2; decade < 1e7; decade *= 10)
        for (double step : {1.0, 2.0, 5.0})
            ticks->addTick(decade * step, QString::number(decade * step, 'g', 6));
    x->setTicker(ticks);
    fit(rect);
    double lo = qInf(), hi = 0;
    for (const auto* f : shown) {
        lo = std::min(lo, f->robotTimePerCompletion_s.low);
        hi = std::max(hi, std::isfinite(f->robotTimePerCompletion_s.high)
                              ? f->robotTimePerCompletion_s.high
                              : f->robotTimePerCompletion_s.mean);
    }
    x->setRange(std::max(1e-3, lo) / 1.15, hi * 1.15);
}

}  // namespace

bool buildFollowingParetoFigure(QCustomPlot& plot, const SweepRates& r) {
    startFigure(plot, QString("Accuracy costs time (b) over %1 seeds: contour following, the "
                              "trade-off and its Pareto front (labels: follow/reposition mm, "
                              "threshold)")
                          .arg(r.seeds));
    // Active settings only: passive trials almost never complete, and their time per completion
    // (tens of thousands of seconds) would crush the active trade-off into a corner. They stay
    // in the tables.
    Shown shown;
    for (const auto& f : r.following)
        if (f.mode == FollowingMode::Active && std::isfinite(f.robotTimePerCompletion_s.mean))
            shown.push_back(&f);
    if (shown.empty()) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    const auto [completion, lc] =
        addTitledPanelWithLegendBelow(grid, 0, 0, /*perLine=*/2, "completion (front circled)",
                                      "robot time per completed trial (s)", "trials completed (%)");
    const auto [distance, ld] = addTitledPanelWithLegendBelow(
        grid, 0, 1, /*perLine=*/2, "path error (front circled)",
        "robot time per completed trial (s)", "mean distance of taps to the contour (mm)");
    const ParetoPanels panels{completion, distance, lc, ld};
    addFollowingSeries(panels, shown);
    addParetoFront(panels, shown);
    labelPaperAndWinners(panels, shown);
    for (QCPAxisRect* rect : {completion, distance}) logTimeAxis(rect, shown);
    return true;
}

bool buildRobustnessFigure(QCustomPlot& plot, const SweepRates& r) {
    startFigure(plot, QString("Robustness over %1 seeds: the whole run again with one fault, "
                              "against the fault-free run")
                          .arg(r.seeds));
    if (r.robustness.empty()) return false;
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    const auto [rect, legend] = addPanelWithLegendBelow(grid, 0, 0, /*perLine=*/3);
    rect->axis(QCPAxis::atLeft)->setLabel("share of active trials (%)");
    std::vector<RobustnessOverSeeds> all{r.robustnessBase};
    all.insert(all.end(), r.robustness.begin(), r.robustness.end());
    QSharedPointer<QCPAxisTickerText> names(new QCPAxisTickerText);
    QVector<double> x, completed, recognised;
    std::vector<SweepEstimate> completedE, recognisedE;
    for (std::size_t i = 0; i < all.size(); ++i) {
        const RobustnessOverSeeds& f = all[i];
        names->addTick(double(i),
                       f.fault == "none" ? QString("none") : QString::fromStdString(f.fault));
        x << double(i);
        completed << 100.0 * f.completed.fraction();
        completedE.push_back({100.0 * f.completed.fraction(), 100.0 * f.completed.low(),
                              100.0 * f.completed.high()});
        // Recognised of the trials run: a path must complete to be named.
        const Rate named{f.recognisedRaw.count, f.completed.total};
        recognised << 100.0 * named.fraction();
        recognisedE.push_back(
            {100.0 * named.fraction(), 100.0 * named.low(), 100.0 * named.high()});
    }
    QCPAxis* bottom = rect->axis(QCPAxis::atBottom);
    bottom->setTicker(names);
    bottom->setTickLabelRotation(-45);  // each label ends at its tick
    intervalBars(addSeries(rect, legend, "active trials completed (Wilson 95 %)", x, completed,
                           seriesColour(0), false),
                 completedE);
    intervalBars(addSeries(rect, legend, "completed and named rightly, paper's rule", x, recognised,
                           seriesColour(2), false),
                 recognisedE);
    auto* base = addSeries(rect, legend, "fault-free run", {-0.5, double(all.size()) - 0.5},
                           {completed[0], completed[0]}, Qt::gray);
    base->setPen(QPen(Qt::gray, 1, Qt::DashLine));
    base->setScatterStyle(QCPScatterStyle::ssNone);
    bottom->setRange(-0.6, double(all.size()) - 0.4);
    double lowest = 100;
    for (const auto& e : completedE) lowest = std::min(lowest, e.low);
    for (const auto& e : recognisedE) lowest = std::min(lowest, e.low);
    rect->axis(QCPAxis::atLeft)->setRange(std::max(0.0, lowest - 5), 101);
    return true;
}

}  // namespace activetouch
