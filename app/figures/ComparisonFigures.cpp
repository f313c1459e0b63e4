#include "app/figures/ComparisonFigures.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "app/figures/FigureLayout.h"
#include "app/figures/FollowingFigures.h"
#include "core/analysis/PairedComparison.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {

/// A part of the result as drawn: what it is, and its colour (as in seed_rates).
struct Part {
    const char* name;
    PairedRate PairedParts::*rate;
    int colour;
};
constexpr int kPartColours[std::size(kPairedParts)] = {0, 3, 2, 7};

/// A dashed line through the panel where B - A is zero: across the panel if `horizontal`.
void markNoDifference(QCPAxisRect* rect, QCPAxis* valueAxis, QCPAxis* other, bool horizontal) {
    auto* zero = new QCPItemStraightLine(rect->parentPlot());
    zero->setClipAxisRect(rect);
    QCPAxis* x = horizontal ? other : valueAxis;
    QCPAxis* y = horizontal ? valueAxis : other;
    zero->point1->setAxes(x, y);
    zero->point2->setAxes(x, y);
    zero->point1->setCoords(0.0, 0.0);
    zero->point2->setCoords(horizontal ? 1.0 : 0.0, horizontal ? 0.0 : 1.0);
    zero->setPen(QPen(Qt::gray, 1, Qt::DashLine));
}

/// Each part's difference with its interval as a point on a bar in the part's colour, the first
/// part at the top, its counts and McNemar's p under its name.
void addDifferences(QCPAxisRect* rect, const PairedComparison& c, const std::vector<Part>& rows) {
    QCPAxis* x = rect->axis(QCPAxis::atBottom);
    QCPAxis* y = rect->axis(QCPAxis::atLeft);
    const int n = static_cast<int>(rows.size());
    QSharedPointer<QCPAxisTickerText> names(new QCPAxisTickerText);
    // Each outcome's name and counts take two lines: the panel is never shorter than them.
    rect->setMinimumSize(0, n * (2 * QFontMetrics(y->tickLabelFont()).height() + 8));
    double lo = 0.0, hi = 0.0;
    for (int i = 0; i < n; ++i) {
        const Part& part = rows[static_cast<std::size_t>(i)];
        const PairedRate& r = c.*part.rate;
        const double at = n - i, d = 100.0 * r.difference();
        const double low = 100.0 * r.differenceLow(), high = 100.0 * r.differenceHigh();
        lo = std::min(lo, low);
        hi = std::max(hi, high);
        names->addTick(at, QString("%1\nA %2/%3, B %4/%5; only A %6, only B %7; p %8")
                               .arg(part.name)
                               .arg(r.a().count)
                               .arg(r.pairs())
                               .arg(r.b().count)
                               .arg(r.pairs())
                               .arg(r.onlyA)
                               .arg(r.onlyB)
                               .arg(r.mcnemarP(), 0, 'g', 2));
        const QColor colour = seriesColour(part.colour);
        QCPGraph* point = rect->parentPlot()->addGraph(y, x);  // keys up the side, values across
        point->setName(QString("B - A: %1").arg(part.name));
        point->setData({at}, {d}, true);
        point->setLineStyle(QCPGraph::lsNone);
        point->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssDisc, colour, 9));
        auto* bar = new QCPErrorBars(y, x);
        bar->setName(QString("95 % interval: %1").arg(part.name));
        bar->setDataPlottable(point);
        bar->setData({d - low}, {high - d});
        bar->setPen(QPen(colour, 2.0));
    }
    y->setTicker(names);
    y->setRange(0.4, n + 0.6);
    const double span = std::max(hi - lo, 2.0);
    x->setRange(lo - 0.08 * span, hi + 0.08 * span);
    markNoDifference(rect, x, y, false);
}

/// Each part's difference after each seed with its interval as a band: how it settles. The value
/// axis spans the bands from a tenth of the seeds on, so that over many seeds the first few, whose
/// intervals may span +-100 points, do not flatten the rest: they run off the panel instead.
void addSettling(QCPAxisRect* rect, QCPLegend* legend, const PairedComparison& c,
                 const std::vector<Part>& rows) {
    double lo = 0.0, hi = 0.0;
    const std::size_t spanFrom = c.soFar.size() / 10;
    for (const Part& part : rows) {
        RunningValue r;
        for (std::size_t i = 0; i < c.soFar.size(); ++i) {
            const PairedRate& at = c.soFar[i].*part.rate;
            if (at.pairs() == 0) continue;
            r.append(double(i + 1), 100.0 * at.difference(), 100.0 * at.differenceLow(),
                     100.0 * at.differenceHigh());
            if (i + 1 < spanFrom) continue;  // before seed n / 10
            lo = std::min(lo, r.low.back());
            hi = std::max(hi, r.high.back());
        }
        addRunningBand(rect, legend, part.name, r, seriesColour(part.colour));
    }
    QSharedPointer<QCPAxisTickerFixed> whole(new QCPAxisTickerFixed);
    whole->setTickStep(1.0);
    whole->setScaleStrategy(QCPAxisTickerFixed::ssMultiples);
    rect->axis(QCPAxis::atBottom)->setTicker(whole);
    rect->axis(QCPAxis::atBottom)->setRange(0.5, double(c.soFar.size()) + 0.5);
    const double span = std::max(hi - lo, 2.0);
    rect->axis(QCPAxis::atLeft)->setRange(lo - 0.05 * span, hi + 0.05 * span);
    markNoDifference(rect, rect->axis(QCPAxis::atLeft), rect->axis(QCPAxis::atBottom), true);
}

}  // namespace

bool buildComparisonFigure(QCustomPlot& plot, const PairedComparison& c, bool stacked) {
    const QString a = QString::fromStdString(c.nameA), b = QString::fromStdString(c.nameB);
    startFigure(plot, QString("%1 (B) against %2 (A), %3 seeds").arg(b, a).arg(c.seeds),
                QString("Robot time per run: A %1 min, B %2 min.")
                    .arg(std::lround(c.meanRobotTimeA_s() / 60.0))
                    .arg(std::lround(c.meanRobotTimeB_s() / 60.0)));
    std::vector<Part> rows;
    for (std::size_t i = 0; i < std::size(kPairedParts); ++i)
        if ((c.*kPairedParts[i].rate).pairs() > 0)
            rows.push_back({kPairedParts[i].name, kPairedParts[i].rate, kPartColours[i]});
    if (rows.empty()) return false;

    QCPLayoutGrid* grid = addFigureRow(plot, 1.0);
    QCPAxisRect* rect = addTitledPanel(grid, 0, "each outcome, B - A",
                                       "B - A with 95 % interval (percentage points)", "");
    addDifferences(rect, c, rows);
    if (c.soFar.empty()) return true;  // made up without its seeds: nothing to settle

    QCPLayoutGrid* below = stacked ? addFigureRow(plot, 1.0) : grid;
    const auto [sofar, legend] = addTitledPanelWithLegendBelow(
        below, 0, stacked ? 0 : 1, /*perLine=*/2, "B - A so far, 95 % intervals", "seeds compared",
        "B - A (percentage points)");
    addSettling(sofar, legend, c, rows);
    // Side by side, the outcomes' names take the left panel's margin: it gets the wider column.
    if (!stacked) grid->setColumnStretchFactors({1.4, 1.0});
    return true;
}

bool buildTrialPairFigure(QCustomPlot& plot, const TrialPairRun& pair) {
    const TrialRun& a = pair.a;
    startFigure(plot, QString("seed %1: %2 trial %3 of %4, as A and B ran it")
                          .arg(pair.seed)
                          .arg(modeName(a.result.mode))
                          .arg(a.trial)
                          .arg(QString::fromStdString(a.label)));
    // Two long entries: the legend goes under the panel, clear of the paths.
    const auto [rect, legend] = addTitledPanelWithLegendBelow(
        addFigureRow(plot, 1.0), 0, 0, 1, QString::fromStdString(a.label), "x (mm)", "y (mm)");
    PathBox box;
    addOutline(rect, legend, a.outline, box);
    if (pair.b.outline.vertices() != a.outline.vertices()) {
        // B placed its object elsewhere: both outlines, B's dashed.
        QCPCurve* outlineB = addOutline(rect, legend, pair.b.outline, box);
        outlineB->setPen(QPen(Qt::darkGray, 1.5, Qt::DashLine));
        outlineB->setName("object in B");
    }
    QCPCurve* firstEnd = nullptr;
    std::vector<Vec2> furthest;
    struct Side {
        const char* which;
        const std::string& name;
        const TrialRun& run;
        QColor colour;
        double dotSize;
    };
    for (const Side& side : {Side{"A", pair.nameA, pair.a, seriesColour(0), 7.0},
                             Side{"B", pair.nameB, pair.b, seriesColour(3), 4.0}}) {
        // How it ended, with its taps; why, if said, on a line of its own.
        const QString ended = QString::fromStdString(endedText(side.run));
        const qsizetype why = ended.indexOf(" (");
        QCPCurve* end =
            addTrialPath(rect, legend, side.run, side.colour, side.dotSize,
                         QString("%1 %2: %3, %4 taps%5")
                             .arg(side.which, QString::fromStdString(side.name), ended.left(why))
                             .arg(side.run.result.taps.size())
                             .arg(why < 0 ? QString() : "\n" + ended.mid(why + 1)),
                         box);
        if (end) {
            if (!firstEnd) firstEnd = end;
            furthest.push_back(side.run.result.furthest.point);
        }
    }
    finishPathPanel(rect, legend, firstEnd, furthest, box, /*legendRoom=*/0.0);
    return true;
}

QStringList writeComparisonFigures(const PairedComparison& comparison, const QString& outDir) {
    const QString dir = figuresDirectory(outDir);
    QCustomPlot plot;
    if (!buildComparisonFigure(plot, comparison)) return {};
    return exportFigure(plot, dir + "/compare", {"png", "pdf", "svg"}, kComparisonFigureSize);
}

QStringList writeTrialPairFigures(const TrialPairRun& pair, const QString& outDir) {
    const QString dir = figuresDirectory(outDir);
    QCustomPlot plot;
    buildTrialPairFigure(plot, pair);
    return exportFigure(plot, dir + "/" + QString::fromStdString(trialPairFileStem(pair)),
                        {"png", "pdf", "svg"}, kTrialPairFigureSize);
}

}  // namespace activetouch
