#include "app/figures/FollowingFigures.h"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "app/figures/FigureExport.h"
#include "app/figures/FigureLayout.h"
#include "app/figures/SweepFigures.h"
#include "app/figures/ValidationFigures.h"
#include "core/analysis/SeedRates.h"
#include "core/run/ExperimentRun.h"
#include "qcustomplot.h"

namespace activetouch {
namespace {

QColor trialColour(int trial) {
    static const QColor palette[] = {QColor(31, 119, 180), QColor(214, 39, 40),
                                     QColor(44, 160, 44),  QColor(148, 103, 189),
                                     QColor(255, 127, 14), QColor(23, 190, 207)};
    return palette[(trial - 1) % 6];
}

bool validated(const RunResult& r) {
    return !r.cancelled && !r.validation.percepts.empty();
}

/// A figure drawn only once the run has its validation.
template <bool (*build)(QCustomPlot&, const RunResult&)>
bool afterValidation(QCustomPlot& plot, const RunResult& r) {
    return validated(r) && build(plot, r);
}

QCPCurve* polyline(QCPAxisRect* rect, const std::vector<Vec2>& points, bool closed) {
    return addPolyline(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft), points, closed);
}

}  // namespace

QCPCurve* addOutline(QCPAxisRect* rect, QCPLegend* legend, const Polygon& outline, PathBox& box) {
    auto* curve = polyline(rect, outline.vertices(), true);
    curve->setPen(QPen(Qt::black, 2));
    curve->setName("object");
    legend->addItem(new QCPPlottableLegendItem(legend, curve));
    for (Vec2 v : outline.vertices()) box.add(v);
    return curve;
}

QCPCurve* addTrialPath(QCPAxisRect* rect, QCPLegend* legend, const TrialRun& t, QColor colour,
                       double dotSize, const QString& name, PathBox& box) {
    auto* path = polyline(rect, t.result.path(), false);
    path->setPen(QPen(colour, 1.0));
    path->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssDisc, colour, dotSize));
    path->setName(name);
    legend->addItem(new QCPPlottableLegendItem(legend, path));
    for (Vec2 v : t.result.path()) box.add(v);
    if (t.result.completed() || t.result.taps.empty()) return nullptr;
    auto* end = polyline(rect, {t.result.path().back()}, false);
    end->setPen(Qt::NoPen);
    end->setScatterStyle(
        QCPScatterStyle(QCPScatterStyle::ssCross, QPen(Qt::black, 2.5), Qt::NoBrush, 13));
    end->setName("where the trial ended");
    return end;
}

void finishPathPanel(QCPAxisRect* rect, QCPLegend* legend, QCPCurve* firstEnd,
                     const std::vector<Vec2>& furthest, const PathBox& box, double legendRoom) {
    if (firstEnd) legend->addItem(new QCPPlottableLegendItem(legend, firstEnd));
    if (!furthest.empty()) {
        // The contour points trials that did not complete got furthest to before they went
        // astray.
        auto* marks = polyline(rect, furthest, false);
        marks->setLineStyle(QCPCurve::lsNone);
        marks->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssDiamond,
                                               QPen(QColor(255, 127, 14), 2.5), Qt::NoBrush, 13));
        marks->setName("furthest along the contour");
        legend->addItem(new QCPPlottableLegendItem(legend, marks));
    }
    const double margin = 8.0;
    const Vec2 lo = box.lo, hi = box.hi;
    setEqualAspectRanges(rect, QCPRange(lo.x - margin, hi.x + margin),
                         QCPRange(lo.y - margin, hi.y + margin + legendRoom * (hi.y - lo.y)));
    if (legendRoom > 0.0) keepLegendClear(rect, legend, hi.x + margin, hi.y + margin);
}

QCPLegend* addPathPanel(QCPAxisRect* rect, const QString& title) {
    rect->axis(QCPAxis::atBottom)->setLabel("x (mm)");
    rect->axis(QCPAxis::atLeft)->setLabel("y (mm)");
    setPanelTitle(rect, title);
    return addLegend(rect);
}

bool buildPathFigure(QCustomPlot& plot, const RunResult& r, FollowingMode mode,
                     const QString& title) {
    std::vector<std::string> labels;
    for (const auto& t : r.trials)
        if (t.result.mode == mode &&
            std::find(labels.begin(), labels.end(), t.label) == labels.end())
            labels.push_back(t.label);
    startFigure(plot, title + classifierTitleNote(r, true));
    if (labels.empty()) return false;
    QCPLayoutGrid* panels = addFigureRow(plot, 1.0);
    const int columns = labels.size() > 2 ? 2 : static_cast<int>(labels.size());
    const QString prefix = mode == FollowingMode::Active ? "ACF" : "PCF";
    for (std::size_t i = 0; i < labels.size(); ++i) {
        auto* rect = new QCPAxisRect(&plot);
        panels->addElement(static_cast<int>(i) / columns, static_cast<int>(i) % columns, rect);
        QCPLegend* legend = addPathPanel(rect, QString::fromStdString(labels[i]));
        PathBox box;
        bool outlineDrawn = false;
        QCPCurve* firstEnd = nullptr;
        std::vector<Vec2> furthest;  // of the trials that did not complete, drawn over the paths
        for (const auto& t : r.trials) {
            if (t.result.mode != mode || t.label != labels[i]) continue;
            if (!outlineDrawn) {
                addOutline(rect, legend, t.outline, box);
                outlineDrawn = true;
            }
            // Later trials draw smaller dots so that overlapping paths stay visible.
            QCPCurve* end = addTrialPath(rect, legend, t, trialColour(t.trial),
                                         std::max(3.0, 7.0 - 1.5 * (t.trial - 1)),
                                         QString("%1%2: %3, %4 taps")
                                             .arg(prefix)
                                             .arg(t.trial)
                                             .arg(trialEndName(t.result.end))
                                             .arg(t.result.taps.size()),
                                         box);
            if (end) {
                // One legend entry per panel for where trials ended, last.
                if (!firstEnd) firstEnd = end;
                furthest.push_back(t.result.furthest.point);
            }
        }
        finishPathPanel(rect, legend, firstEnd, furthest, box);
    }
    return true;
}

namespace {

using ShapeTrials = std::vector<std::pair<std::string, std::vector<const TrialRun*>>>;

/// One row per shape traced, in the order of the confusion tables beside the figure (the
/// templates' order: the paper's rectangle, cross, C, L).
ShapeTrials shapesTraced(const RunResult& r) {
    ShapeTrials byShape;
    for (const std::string& shape : recognitionConfusion(r).labels) {
        std::vector<const TrialRun*> trials;
        for (const auto& t : r.trials)
            if (t.recognised && t.label == shape) trials.push_back(&t);
        if (!trials.empty()) byShape.emplace_back(shape, std::move(trials));
    }
    return byShape;
}

/// A path histogram as a heat map in `rect`, coloured on `scale`.
void addHistogramPanel(QCPAxisRect* rect, const PathHistogram& h, const QString& title,
                       QCPColorScale* scale) {
    setPanelTitle(rect, title);
    rect->axis(QCPAxis::atBottom)->setLabel("x bin");
    rect->axis(QCPAxis::atLeft)->setLabel("y bin");
    auto* map = new QCPColorMap(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    map->data()->setSize(h.bins, h.bins);
    map->data()->setRange(QCPRange(0.5, h.bins - 0.5), QCPRange(0.5, h.bins - 0.5));
    for (int iy = 0; iy < h.bins; ++iy)
        for (int ix = 0; ix < h.bins; ++ix) map->data()->setCell(ix, iy, h.at(ix, iy));
    map->setInterpolate(false);
    map->setColorScale(scale);
    // Square bins: the axes widen beyond the histogram to fit the panel, so ticks are labelled
    // only where there are bins.
    setEqualAspectRanges(rect, QCPRange(0, h.bins), QCPRange(0, h.bins));
    QSharedPointer<QCPAxisTickerText> ticks(new QCPAxisTickerText);
    const int step = std::max(1, h.bins / 4);
    for (int b = 0; b <= h.bins; b += step) ticks->addTick(b, QString::number(b));
    rect->axis(QCPAxis::atBottom)->setTicker(ticks);
    rect->axis(QCPAxis::atLeft)->setTicker(ticks);
}

/// What the paper's rule named a trial; the smoothed rule's name on a line of its own when the
/// two disagree, so the title stays as narrow as its panel.
QString trialTitle(const TrialRun& t) {
    const auto& rec = t.recognition;
    QString title = QString("ACF%1%2 -> %3")
                        .arg(t.trial)
                        .arg(t.result.end == TrialEnd::Completed ? "" : " (incomplete)",
                             QString::fromStdString(rec.predicted));
    if (rec.predictedSmoothed != rec.predicted)
        title += QString("\nsmoothed: %1").arg(QString::fromStdString(rec.predictedSmoothed));
    return title;
}

/// Distances to every template, one bar group per template, bars lying along the distance axis
/// so that the templates' names stack and never run into each other. The legend goes in a row
/// of its own under the bars: inside the panel it would hide the longest bars, which are the
/// ones a reader compares.
void addDistancePanel(QCustomPlot& plot, QCPLayoutGrid* grid, int row, int column,
                      const std::vector<const TrialRun*>& trials, const RunResult& r) {
    const auto [dr, barLegend] = addPanelWithLegendBelow(grid, row, column, /*perLine=*/0);
    // On two lines: the title is centred over the bars, which the templates' names push right in
    // a narrow panel.
    setPanelTitle(dr, "distances\n(paper's rule)");
    QCPAxis* templateAxis = dr->axis(QCPAxis::atLeft);
    QCPAxis* distanceAxis = dr->axis(QCPAxis::atBottom);
    distanceAxis->setLabel("Euclidean distance");
    distanceAxis->ticker()->setTickCount(3);  // the panel is narrow; labels like 0.025 are wide
    QSharedPointer<QCPAxisTickerText> ticker(new QCPAxisTickerText);
    // One named row per template: the panel is never shorter than their names stacked.
    dr->setMinimumSize(0, static_cast<int>(r.templates.size()) *
                              (QFontMetrics(templateAxis->tickLabelFont()).height() + 6));
    auto* group = new QCPBarsGroup(&plot);
    double longest = 0.0;
    for (std::size_t k = 0; k < trials.size(); ++k) {
        auto* bars = new QCPBars(templateAxis, distanceAxis);
        bars->setBrush(trialColour(trials[k]->trial));
        bars->setPen(Qt::NoPen);
        bars->setWidth(0.35);
        bars->setBarsGroup(group);
        bars->setName(QString("ACF%1").arg(trials[k]->trial));
        barLegend->addItem(new QCPPlottableLegendItem(barLegend, bars));
        QVector<double> keys, values;
        int i = 0;
        for (const auto& t : r.templates) {
            keys << ++i;
            values << trials[k]->recognition.distances.at(t.shape);
            longest = std::max(longest, values.back());
            if (k == 0) ticker->addTick(i, QString::fromStdString(t.shape));
        }
        bars->setData(keys, values);
    }
    templateAxis->setTicker(ticker);
    templateAxis->setRange(0.4, r.templates.size() + 0.6);
    templateAxis->setRangeReversed(true);  // the first template on top, as in the legend
    distanceAxis->setRange(0, longest * 1.1);
}

}  // namespace

bool buildRecognitionFigure(QCustomPlot& plot, const RunResult& r) {
    const int bins = r.spec.recognition.bins;
    const QString title = QString("Figure 9 - recognition from %1 × %1 path histograms").arg(bins);
    if (r.templates.empty()) {
        // Nothing recognised (no recognition step, or no run yet): no accuracy to claim.
        startFigure(plot, title);
        return false;
    }
    startFigure(plot, title,
                QString("Named rightly: %1 % (paper's rule),\n%2 % (smoothed histograms, "
                        "σ = %3 bins).")
                    .arg(100.0 * r.recognitionAccuracy, 0, 'f', 0)
                    .arg(100.0 * r.recognitionAccuracySmoothed, 0, 'f', 0)
                    .arg(r.spec.recognition.smoothingSigmaBins));
    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    const ShapeTrials byShape = shapesTraced(r);
    int maxTrials = 0;
    for (const auto& [shape, trials] : byShape)
        maxTrials = std::max(maxTrials, static_cast<int>(trials.size()));
    auto* scale = new QCPColorScale(&plot);
    scale->setType(QCPAxis::atRight);
    scale->axis()->setLabel("fraction of taps per bin");
    scale->setDataRange(QCPRange(0, 0.05));
    scale->setGradient(heatGradient());
    int row = 0;
    for (const auto& [shape, trials] : byShape) {
        auto* tr = new QCPAxisRect(&plot);
        grid->addElement(row, 0, tr);
        for (const auto& t : r.templates)
            if (t.shape == shape)
                addHistogramPanel(
                    tr, t.raw, QString("template: %1").arg(QString::fromStdString(shape)), scale);
        for (std::size_t k = 0; k < trials.size(); ++k) {
            auto* pr = new QCPAxisRect(&plot);
            grid->addElement(row, 1 + static_cast<int>(k), pr);
            addHistogramPanel(pr, trials[k]->recognition.raw, trialTitle(*trials[k]), scale);
        }
        addDistancePanel(plot, grid, row, 1 + maxTrials, trials, r);
        ++row;
    }
    grid->addElement(0, 2 + maxTrials, scale);
    return true;
}

const std::vector<RunFigure>& runFigures() {
    // Beyond Figure 5 every figure needs the validation the run may not have reached.
    static const std::vector<RunFigure> figures{
        {"figure5_taps",
         [](QCustomPlot& plot, const RunResult& r) {
             buildTapFigure(plot, r);
             return true;
         },
         FigureSize::physical(kDoubleColumn_mm, 122, kFigureDpi)},
        {"figure6_errors",
         [](QCustomPlot& plot, const RunResult& r) {
             if (!validated(r)) return false;
             buildErrorFigure(plot, r);
             return true;
         },
         FigureSize::physical(kDoubleColumn_mm, 115, kFigureDpi)},
        {"figure6_continuous_angle",
         [](QCustomPlot& plot, const RunResult& r) {
             return validated(r) && buildContinuousAngleFigure(plot, r);
         },
         FigureSize::physical(kDoubleColumn_mm, 95, kFigureDpi)},
        {"figure7_passive_paths",
         [](QCustomPlot& plot, const RunResult& r) {
             return validated(r) && buildPathFigure(plot, r, FollowingMode::Passive,
                                                    "Figure 7 - passive contour following (PCF)");
         },
         FigureSize::physical(kDoubleColumn_mm, 160, kFigureDpi)},
        {"figure8_active_paths",
         [](QCustomPlot& plot, const RunResult& r) {
             return validated(r) && buildPathFigure(plot, r, FollowingMode::Active,
                                                    "Figure 8 - active contour following (ACF)");
         },
         FigureSize::physical(kDoubleColumn_mm, 167, kFigureDpi)},
        {"figure9_recognition", afterValidation<buildRecognitionFigure>,
         FigureSize::physical(kDoubleColumn_mm, 210, kFigureDpi)},
        {"sweep_a_sequential_perception", afterValidation<buildPerceptionSweepFigure>,
         FigureSize::physical(kDoubleColumn_mm, 89, kFigureDpi)},
        {"sweep_b_following", afterValidation<buildFollowingSweepFigure>,
         FigureSize::physical(kDoubleColumn_mm, 100, kFigureDpi)},
        {"sweep_c_compute", afterValidation<buildComputeSweepFigure>,
         FigureSize::physical(kDoubleColumn_mm, 89, kFigureDpi)},
    };
    return figures;
}

QStringList writeRunFigures(const RunResult& result, const QString& outDir, double widthMm) {
    const QString dir = figuresDirectory(outDir);
    QStringList written;
    QCustomPlot plot;
    for (const RunFigure& figure : runFigures()) {
        // Built on a plot of the figure's shape: a figure may lay itself out for it.
        FigureSize size = figure.size;
        if (widthMm > 0.0) size = FigureSize::physical(widthMm, size.height_mm, size.dpi);
        plot.resize(layoutSize(plot, size));
        if (!figure.build(plot, result)) continue;
        if (widthMm > 0.0) size = figureSizeFor(plot, figure.size, widthMm);
        written << exportFigure(plot, dir + "/" + figure.file, {"png", "pdf", "svg"}, size);
    }
    return written;
}

}  // namespace activetouch
