#include "app/figures/ValidationFigures.h"

#include <algorithm>
#include <cmath>

#include "app/figures/FigureFitting.h"
#include "app/figures/FigureLayout.h"
#include "app/figures/FigureReflow.h"
#include "core/run/ExperimentRun.h"
#include "core/stats/Intervals.h"
#include "qcustomplot.h"

namespace activetouch {
namespace {

QCPAxisRect* addPanel(QCPLayoutGrid* grid, int row, int column, const QString& xLabel,
                      const QString& yLabel) {
    auto* rect = new QCPAxisRect(grid->parentPlot());
    grid->addElement(row, column, rect);
    rect->axis(QCPAxis::atBottom)->setLabel(xLabel);
    rect->axis(QCPAxis::atLeft)->setLabel(yLabel);
    return rect;
}

QSharedPointer<QCPAxisTickerText> orientationTicker(const ClassSet& cs) {
    // Every orientation by name up to twelve; beyond, a label every quarter of the list (36
    // names in a column would overlap).
    QSharedPointer<QCPAxisTickerText> t(new QCPAxisTickerText);
    const std::size_t n = cs.orientationsDeg.size(), step = n > 12 ? n / 4 : 1;
    for (std::size_t o = 0; o < n; o += step)
        t->addTick(double(o),
                   QString::fromStdString(ClassSet::orientationName(cs.orientationsDeg[o])));
    return t;
}

void shadeValidRange(QCPAxisRect* rect, const RunResult& r, double yMax, double dataTop) {
    const auto& vr = r.validation.validRange;
    auto* band = new QCPItemRect(rect->parentPlot());
    band->setClipAxisRect(rect);
    for (auto* pos : {band->topLeft, band->bottomRight}) {
        pos->setAxes(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
        pos->setAxisRect(rect);
    }
    // The band spans the panel's height, whatever its top.
    band->topLeft->setTypeY(QCPItemPosition::ptAxisRectRatio);
    band->bottomRight->setTypeY(QCPItemPosition::ptAxisRectRatio);
    band->topLeft->setCoords(vr.first - 0.5, 0.0);
    band->bottomRight->setCoords(vr.last + 0.5, 1.0);
    band->setPen(Qt::NoPen);
    band->setBrush(QColor(46, 160, 67, 45));
    auto* label = new QCPItemText(rect->parentPlot());
    label->setClipAxisRect(rect);
    label->position->setAxes(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    label->position->setAxisRect(rect);
    label->position->setCoords(0.5 * (vr.first + vr.last), yMax * 0.97);
    label->setPositionAlignment(Qt::AlignTop | Qt::AlignHCenter);
    label->setText(QString::fromStdString(vr.text()));
    label->setColor(QColor(30, 110, 45));
    // Above the data, however wide the label is against the band at the panel's size.
    keepTextAboveData(rect, label, 0.0, dataTop);
}

}  // namespace

void buildTapFigure(QCustomPlot& plot, const RunResult& r) {
    const ClassSet& cs = r.classes;
    const int O = static_cast<int>(cs.orientationsDeg.size());
    const int K = r.classifier.trained() ? r.classifier.taxelCount() : kFingertipTaxels;
    const int firstSet =
        r.spec.training.trainingSets.empty() ? 1 : r.spec.training.trainingSets.front();
    // At most eight panels: with more orientations, eight spread evenly round the circle (the
    // others look alike, turned), and the caption says so.
    constexpr int kMaxPanels = 8;
    std::vector<int> shown;
    for (int i = 0; i < std::min(O, kMaxPanels); ++i)
        shown.push_back(O <= kMaxPanels ? i : i * O / kMaxPanels);
    // Two rows of panels: a narrow figure wraps them (reflowPanels).
    const int columns = shown.size() > 4 ? 4 : shown.size() >= 4 ? 2 : 1;
    startFigure(plot, QString("Figure 5 - taps across each edge (data set %1)").arg(firstSet),
                O <= kMaxPanels ? QString()
                                : QString("%1 of the %2 trained orientations, evenly spread.")
                                      .arg(shown.size())
                                      .arg(O));
    QCPLayoutGrid* panels = addFigureRow(plot, 1.0);
    panels->setProperty(kUsualRows, 2);  // the paper's four orientations
    for (std::size_t panel = 0; panel < shown.size(); ++panel) {
        const int o = shown[panel];
        auto* rect =
            addPanel(panels, static_cast<int>(panel) / columns, static_cast<int>(panel) % columns,
                     "tap position across the edge (mm; plane to air)", "pressure (normalised)");
        setPanelTitle(rect, QString::fromStdString(ClassSet::orientationName(
                                cs.orientationsDeg[static_cast<std::size_t>(o)])) +
                                " edge");
        // Normalise each panel to a maximum of one, as the paper does.
        double peak = 0.0;
        for (const auto& t : r.taps)
            if (t.dataSet == firstSet && cs.orientationIndexOf(t.cls) == o)
                for (double v : t.record.tap.samples) peak = std::max(peak, v);
        for (int k = 0; k < K; ++k) {
            auto* g = plot.addGraph(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
            g->setPen(QPen(taxelColour(k), 1.2));
            g->setName(QString("taxel %1").arg(k));
            QVector<double> x, y;
            for (const auto& t : r.taps) {
                if (t.dataSet != firstSet || cs.orientationIndexOf(t.cls) != o) continue;
                const int T = t.record.tap.sampleCount();
                for (int s = 0; s < T; ++s) {
                    x << cs.positionOf(t.cls) - 0.5 + double(s) / T;
                    y << (peak > 0 ? t.record.tap.at(s, k) / peak : 0.0);
                }
                x << qQNaN();  // a gap between taps
                y << qQNaN();
            }
            g->setData(x, y, true);
        }
        rect->axis(QCPAxis::atBottom)->setRange(0.5, cs.positions + 0.5);
        integerTicks(rect->axis(QCPAxis::atBottom), 1.0);
        rect->axis(QCPAxis::atLeft)->setRange(0.0, 1.05);
    }
    // Legend: taxel colours, in its own row at the bottom.
    QCPLegend* legend = addLegendRow(plot, 6);
    for (int k = 0; k < K && k < plot.graphCount(); ++k)
        legend->addItem(new QCPPlottableLegendItem(legend, plot.graph(k)));
}

QString classifierTitleNote(const RunResult& r, bool following) {
    QString note;
    if (const double kernel = r.spec.classifier.kernelSigma_bins; kernel > 0.0)
        note += QString("; kernel %1 bins").arg(kernel);
    if (following && r.classifierRetrainedOnTaps > 0)
        note += QString("; trained on all %1 data sets").arg(r.spec.training.dataSets);
    return note;
}

namespace {

/// A colour scale for `map` beside `rect` in `grid` at `column` + 1, its top fixed so that runs
/// compare by eye, its height the panel's; cells without data blank.
void addHeatScale(QCustomPlot& plot, QCPLayoutGrid* grid, int column, QCPAxisRect* rect,
                  QCPColorMap* map, const QString& unit, double top) {
    map->setInterpolate(false);
    map->setTightBoundary(false);
    auto* scale = new QCPColorScale(&plot);
    grid->addElement(0, column + 1, scale);
    scale->setType(QCPAxis::atRight);
    scale->axis()->setLabel(unit);
    map->setColorScale(scale);
    QCPColorGradient gradient = heatGradient();
    gradient.setNanHandling(QCPColorGradient::nhTransparent);
    map->setGradient(gradient);
    map->setDataRange(QCPRange(0, top));
    alignWithPanel(scale, rect);
}

/// A map over the class grid (position across, orientation up) of one value per class.
template <typename Value>
void fillClassMap(QCPAxisRect* rect, QCPColorMap* map, const RunResult& r, Value value) {
    const ClassSet& cs = r.classes;
    const int O = static_cast<int>(cs.orientationsDeg.size()), P = cs.positions;
    map->data()->setSize(P, O);
    map->data()->setRange(QCPRange(1, P), QCPRange(0, O - 1));
    for (const auto& e : r.validation.byClass)
        map->data()->setCell(e.position - 1, e.orientationIndex, value(e));
    rect->axis(QCPAxis::atBottom)->setRange(0.5, P + 0.5);
    rect->axis(QCPAxis::atLeft)->setRange(-0.5, O - 0.5);
    rect->axis(QCPAxis::atLeft)->setTicker(orientationTicker(cs));
    QStringList names;
    for (double deg : cs.orientationsDeg)
        names << QString::fromStdString(ClassSet::orientationName(deg));
    rect->axis(QCPAxis::atLeft)->setProperty(kCategoryNames, names);
}

/// Panels C and D of Figure 6: an error by position, mean over orientations ± 1 s.d., the
/// valid range shaded.
void fillErrorLine(QCustomPlot& plot, QCPAxisRect* rect, const RunResult& r, bool angle) {
    const int P = r.classes.positions;
    const auto& mean = angle ? r.validation.angleMean : r.validation.positionMean;
    const auto& sd = angle ? r.validation.angleStd : r.validation.positionStd;
    rect->axis(QCPAxis::atBottom)->setLabel("position (mm; 1 = plane, 18 = air)");
    rect->axis(QCPAxis::atLeft)->setLabel(angle ? "angle error (°)" : "position error (mm)");
    setPanelTitle(rect, angle ? "C  angle error, mean over orientations ± 1 s.d."
                              : "D  position error, mean over orientations ± 1 s.d.");
    auto* g = plot.addGraph(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    QVector<double> x, y, e;
    double top = 0.0;
    for (int p = 1; p <= P; ++p) {
        x << p;
        y << mean[static_cast<std::size_t>(p - 1)];
        e << sd[static_cast<std::size_t>(p - 1)];
        top = std::max(top, y.back() + e.back());
    }
    g->setData(x, y, true);
    g->setPen(QPen(QColor(31, 119, 180), 2));
    g->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, 6));
    auto* bars = new QCPErrorBars(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    bars->setDataPlottable(g);
    bars->setData(e);
    bars->setPen(QPen(QColor(31, 119, 180)));
    const double yMax = std::max(top * 1.15, angle ? 10.0 : 1.0);
    rect->axis(QCPAxis::atBottom)->setRange(0.5, P + 0.5);
    integerTicks(rect->axis(QCPAxis::atBottom), 1.0);
    rect->axis(QCPAxis::atLeft)->setRange(0.0, yMax);
    shadeValidRange(rect, r, yMax, yMax / 1.15);
}

}  // namespace

void buildErrorFigure(QCustomPlot& plot, const RunResult& r) {
    const ClassSet& cs = r.classes;
    // Fixed scales so that runs compare by eye; position errors above a third of the window are
    // all "far off" and share the top colour.
    const double maxPosition = std::ceil((cs.positions - 1) * cs.positionStep_mm / 3.0);
    startFigure(plot, "Figure 6 - offline validation" + classifierTitleNote(r, false),
                QString("Over %1 test taps: angle error %2°, position error %3 mm;\nnoise "
                        "floor %4 counts. In B, errors of %5 mm or more share the top colour.")
                    .arg(r.validation.percepts.size())
                    .arg(r.validation.angleError_deg, 0, 'f', 1)
                    .arg(r.validation.positionError_mm, 0, 'f', 2)
                    .arg(r.noiseFloor_counts, 0, 'f', 1)
                    .arg(maxPosition));
    // The heatmaps side by side (each with its scale) above the two line panels; a narrow figure
    // wraps them one to a line (reflowPanels). Left edges aligned.
    auto* left = new QCPMarginGroup(&plot);
    QCPLayoutGrid* heatRow = addFigureRow(plot, 1.0);
    for (int h = 0; h < 2; ++h) {
        const bool angle = h == 0;
        const int column = 2 * h;
        auto* rect =
            addPanel(heatRow, 0, column, "position (mm; 1 = plane, 18 = air)", "edge orientation");
        rect->setMarginGroup(QCP::msLeft, left);
        setPanelTitle(rect, angle ? "A  angle error" : "B  position error");
        auto* map = new QCPColorMap(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
        fillClassMap(rect, map, r, [&](const ClassError& e) {
            return angle ? e.angleError_deg : e.positionError_mm;
        });
        integerTicks(rect->axis(QCPAxis::atBottom), 1.0);
        addHeatScale(plot, heatRow, column, rect, map,
                     angle ? "angle error (°)" : "position error (mm)",
                     angle ? 180.0 : maxPosition);
    }
    // The line panels side by side below the heatmaps.
    QCPLayoutGrid* lineRow = addFigureRow(plot, 1.0);
    for (int l = 0; l < 2; ++l) {
        auto* rect = new QCPAxisRect(&plot);
        lineRow->addElement(0, l, rect);
        rect->setMarginGroup(QCP::msLeft, left);
        fillErrorLine(plot, rect, r, l == 0);
    }
    heatRow->setColumnStretchFactors({1.0, 0.06, 1.0, 0.06});
    heatRow->setProperty(kColumnGroup, 2);
}

namespace {

constexpr int kAngleBins = 36, kOffsetBins = 9;  // 10 degrees; -4.5..4.5 mm

/// Following taps perceived as an edge, binned by the true edge angle and offset: each cell's
/// angle errors; the taps binned into `taps`.
std::vector<std::vector<double>> followingCells(const RunResult& r, int& taps) {
    std::vector<std::vector<double>> cells(static_cast<std::size_t>(kAngleBins * kOffsetBins));
    taps = 0;
    for (const TrialRun& t : r.trials)
        for (const FollowedTap& f : t.result.taps) {
            if (!f.percept.continuous || f.percept.region != Region::Edge) continue;
            const double offset = -f.contourDistance_mm;
            const int a = std::clamp(static_cast<int>(f.trueEdgeDeg / 10.0), 0, kAngleBins - 1);
            const int o = static_cast<int>(std::floor(offset + 4.5));
            if (o < 0 || o >= kOffsetBins) continue;
            cells[static_cast<std::size_t>(a * kOffsetBins + o)].push_back(
                angleDifferenceDeg(f.percept.orientationDeg, f.trueEdgeDeg));
            ++taps;
        }
    return cells;
}

void fillFollowingMap(QCPAxisRect* rect, QCPColorMap* map,
                      const std::vector<std::vector<double>>& cells) {
    map->data()->setSize(kOffsetBins, kAngleBins);
    map->data()->setRange(QCPRange(-4.0, 4.0), QCPRange(5.0, 355.0));
    for (int a = 0; a < kAngleBins; ++a)
        for (int o = 0; o < kOffsetBins; ++o) {
            const auto& c = cells[static_cast<std::size_t>(a * kOffsetBins + o)];
            map->data()->setCell(o, a, stats::medianOr(c, std::nan("")));
        }
    rect->axis(QCPAxis::atBottom)->setRange(-4.5, 4.5);
    rect->axis(QCPAxis::atLeft)->setRange(0.0, 360.0);
    integerTicks(rect->axis(QCPAxis::atLeft), 90.0);
}

}  // namespace

bool buildContinuousAngleFigure(QCustomPlot& plot, const RunResult& r) {
    const ValidationResult& v = r.validation;
    if (!v.continuousValidated) return false;
    constexpr double kTop = 20.0;  // degrees: the colour scale's top, fixed so runs compare
    int followingTaps = 0;
    const auto cells = followingCells(r, followingTaps);
    auto text = [](double x) { return x >= 0.0 ? QString::number(x, 'f', 2) : QString("-"); };
    startFigure(
        plot, "Continuous edge percept - angle error" + classifierTitleNote(r, false),
        QString("Median angle error inside the valid range: %1° on the test taps (A, at the "
                "trained orientations), %2° along the paths (B's taps inside the valid range, away "
                "from corners, %3 taps).\nB: %4 following taps at the edges the trials met; "
                "cells without taps are blank; errors of %5° or more share the top colour.")
            .arg(text(v.continuousMedianAngleErrorInRange_deg))
            .arg(text(r.pathMedianAngleError_deg))
            .arg(r.pathAngleTaps)
            .arg(followingTaps)
            .arg(kTop));
    // Side by side, each with its scale; a narrow figure wraps them (reflowPanels).
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    for (int panel = 0; panel < 2; ++panel) {
        const int column = 2 * panel;
        auto* rect = panel == 0
                         ? addPanel(grid, 0, column, "position (mm; 1 = plane, 18 = air)",
                                    "trained edge orientation")
                         : addPanel(grid, 0, column, "true offset from the edge (mm; + air side)",
                                    "true edge normal (°)");
        setPanelTitle(rect, panel == 0 ? "A  test taps, median per class"
                                       : "B  following taps, median per cell");
        auto* map = new QCPColorMap(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
        if (panel == 0)
            fillClassMap(rect, map, r, [](const ClassError& e) {
                return e.continuousTaps > 0 ? e.continuousAngleError_deg : std::nan("");
            });
        else
            fillFollowingMap(rect, map, cells);
        addHeatScale(plot, grid, column, rect, map, "angle error (°)", kTop);
    }
    grid->setColumnStretchFactors({1.0, 0.06, 1.0, 0.06});
    grid->setProperty(kColumnGroup, 2);
    return true;
}

}  // namespace activetouch
