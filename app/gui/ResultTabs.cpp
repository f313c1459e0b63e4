#include "app/gui/ResultTabs.h"

#include <QColor>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QScrollBar>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>
#include <tuple>

#include "app/figures/FollowingFigures.h"
#include "app/figures/SweepFigures.h"
#include "app/figures/ValidationFigures.h"
#include "app/gui/PlotPanel.h"
#include "core/analysis/SeedRates.h"
#include "core/analysis/SweepRates.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {

/// `table` as one rule's confusion; the cells off the diagonal that are not zero stand out.
void fillConfusion(QTableWidget* table, const RecognitionConfusion& confusion, bool smoothed) {
    const auto& counts = smoothed ? confusion.smoothed : confusion.raw;
    const int n = static_cast<int>(confusion.labels.size());
    table->clear();
    table->setRowCount(n);
    table->setColumnCount(n);
    QStringList names;
    for (const auto& s : confusion.labels) names << QString::fromStdString(s);
    table->setHorizontalHeaderLabels(names);
    table->setVerticalHeaderLabels(names);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const int count = counts[std::size_t(a)][std::size_t(b)];
            auto* cell = new QTableWidgetItem(QString::number(count));
            cell->setToolTip(
                QObject::tr("%1 path(s) of the %2 named %3").arg(count).arg(names[a], names[b]));
            if (a != b && count > 0) {
                cell->setBackground(QColor(255, 220, 200));
                cell->setForeground(QColor(Qt::black));  // readable in a dark theme too
            }
            table->setItem(a, b, cell);
        }
    // The shapes' names whole: columns as wide as their names, never elided.
    table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    table->verticalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    table->setTextElideMode(Qt::ElideNone);
    // As tall as its rows up to eight shapes; more scroll.
    table->setMaximumHeight(table->horizontalHeader()->sizeHint().height() +
                            8 * table->verticalHeader()->defaultSectionSize() +
                            table->horizontalScrollBar()->sizeHint().height() +
                            2 * table->frameWidth());
}

QString recognitionHint() {
    return QObject::tr(
        "The active paths are recognised after active following: click Run whole protocol, "
        "or Run following once the classifier is trained.");
}

}  // namespace

ValidationTab::ValidationTab(QWidget* parent) : QTabWidget(parent) {
    taps_ = new PlotPanel("figure5_taps");
    errors_ = new PlotPanel("figure6_errors");
    addTab(errors_, tr("Errors by orientation and position (Figure 6)"));
    addTab(taps_, tr("Taps across each edge (Figure 5)"));
    continuous_ = new PlotPanel("figure6_continuous_angle");
    addTab(continuous_, tr("Continuous percept angle error"));
    continuous_->setEmptyHint(
        tr("Experiments that follow with the continuous edge percept (following: percept "
           "continuous, as general_shapes.json) show its angle error here: on the test taps and "
           "along the followed paths, at any edge angle."));
    const QString training =
        tr("Click Run whole protocol, or Run training & validation, to tap the "
           "training and test sets on the rig and validate the classifier.");
    taps_->setEmptyHint(training);
    errors_->setEmptyHint(training);
}

void ValidationTab::showRun(const std::shared_ptr<const RunResult>& result) {
    const RunResult& r = *result;
    if (!r.taps.empty()) buildTapFigure(taps_->plot(), r);
    if (!r.validation.byClass.empty()) {
        buildErrorFigure(errors_->plot(), r);
        // Figure 6 lays itself out for the plot's shape: an export in a single column draws it
        // again for that shape.
        errors_->setRebuild([result](QCustomPlot& plot) { buildErrorFigure(plot, *result); });
    }
    // A run of the discrete percept leaves no continuous figure behind from an earlier run.
    QCustomPlot& c = continuous_->plot();
    if (!buildContinuousAngleFigure(c, r)) {
        c.clearPlottables();
        c.clearItems();
        c.plotLayout()->clear();
        continuous_->setRebuild({});
    } else {
        continuous_->setRebuild(
            [result](QCustomPlot& plot) { buildContinuousAngleFigure(plot, *result); });
    }
    for (auto* p : {taps_, errors_, continuous_}) p->plot().replot();
}

RecognitionTab::RecognitionTab(QWidget* parent) : QSplitter(Qt::Vertical, parent) {
    figure_ = new PlotPanel("figure9_recognition");
    addWidget(figure_);
    auto* confusionBox = new QGroupBox(
        tr("Confusion over the recognised trials (rows: the shape traced; columns: the shape "
           "named)"));
    auto* confusionRow = new QHBoxLayout(confusionBox);
    for (auto [table, title, name] :
         {std::tuple{&raw_, &rawTitle_, "confusionPaperRule"},
          std::tuple{&smoothed_, &smoothedTitle_, "confusionSmoothed"}}) {
        auto* column = new QVBoxLayout;
        *title = new QLabel;
        *table = new QTableWidget;
        (*table)->setObjectName(name);
        (*table)->setEditTriggers(QAbstractItemView::NoEditTriggers);
        // As tall as its rows: the figure above takes the rest of the height.
        (*table)->setSizeAdjustPolicy(QAbstractScrollArea::AdjustToContents);
        (*table)->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
        column->addWidget(*title);
        column->addWidget(*table);
        confusionRow->addLayout(column, 1);
    }
    confusionBox->setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Maximum);
    addWidget(confusionBox);
    setStretchFactor(0, 4);
    figure_->setEmptyHint(recognitionHint());
}

void RecognitionTab::showRun(const RunResult& r) {
    figure_->setEmptyHint(r.spec.recognition.enabled
                              ? recognitionHint()
                              : tr("This experiment has no recognition step: add a "
                                   "\"recognition\" section, as experiments/paper.json has, "
                                   "to recognise the shapes from the traced paths."));
    buildRecognitionFigure(figure_->plot(), r);
    figure_->plot().replot();
    const RecognitionConfusion confusion = recognitionConfusion(r);
    fillConfusion(raw_, confusion, false);
    fillConfusion(smoothed_, confusion, true);
    rawTitle_->setText(
        tr("paper's rule: %1 % named rightly").arg(100.0 * r.recognitionAccuracy, 0, 'f', 0));
    smoothedTitle_->setText(tr("smoothed histograms (σ = %1 bins): %2 % named rightly")
                                .arg(r.spec.recognition.smoothingSigmaBins)
                                .arg(100.0 * r.recognitionAccuracySmoothed, 0, 'f', 0));
}

SweepsTab::SweepsTab(QWidget* parent) : QWidget(parent) {
    tabs_ = new QTabWidget;
    perception_ = new PlotPanel("sweep_a_sequential_perception");
    following_ = new PlotPanel("sweep_b_following");
    compute_ = new PlotPanel("sweep_c_compute");
    tabs_->addTab(perception_, tr("(a) taps per decision"));
    tabs_->addTab(following_, tr("(b) following steps"));
    tabs_->addTab(compute_, tr("(c) compute"));
    perceptionSeeds_ = new PlotPanel("seeds_sweep_a_perception");
    pareto_ = new PlotPanel("seeds_sweep_b_pareto_front");
    tabs_->addTab(perceptionSeeds_, tr("(a) over seeds"));
    tabs_->addTab(pareto_, tr("(b) Pareto front over seeds"));
    setToolTip(tr("Run an experiment with sweeps, such as experiments/accuracy_vs_time.json"));
    for (PlotPanel* p : {perception_, following_, compute_})
        p->setEmptyHint(
            tr("No sweeps measured yet. Open experiments/accuracy_vs_time.json (or any "
               "experiment with a \"sweeps\" section) and click Run whole protocol "
               "to measure what accuracy costs in time."));
    for (PlotPanel* p : {perceptionSeeds_, pareto_})
        p->setEmptyHint(
            tr("No sweeps over seeds yet. Open experiments/accuracy_vs_time.json and click "
               "Run over seeds in the Seeds tab to see each sweep as means over seeds with "
               "their 95 % intervals, and the following settings set against the paper's."));
    pickedLabel_ = new QLabel(tr("Click a point of (a) or (b) to see its setting."));
    pickedLabel_->setObjectName("sweepPicked");
    pickedLabel_->setWordWrap(true);
    pickedLabel_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    runPicked_ = new QPushButton(tr("Follow with this setting"));
    runPicked_->setObjectName("sweepRunPicked");
    runPicked_->setToolTip(
        tr("Sets the protocol's follow step, repositioning step and belief threshold to the "
           "point's and runs following with the classifier the last run trained"));
    runPicked_->setEnabled(false);
    runPicked_->hide();  // until sweeps are shown
    runStandard_ = new QPushButton(tr("Run the standard sweeps on this experiment"));
    runStandard_->setObjectName("sweepRunStandard");
    runStandard_->setToolTip(
        tr("Runs the experiment shown with the sweeps of experiments/accuracy_vs_time.json: "
           "belief thresholds 0.5-0.999, follow steps 1-4 mm, repositioning 0.5-2 mm, "
           "histogram bins and samples per tap"));
    runStandard_->hide();
    auto* bar = new QHBoxLayout;
    bar->addWidget(pickedLabel_, 1);
    bar->addWidget(runPicked_);
    bar->addWidget(runStandard_);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(tabs_, 1);
    layout->addLayout(bar);
    for (auto [panel, following] : {std::pair{perception_, false}, std::pair{following_, true}}) {
        // A click (not a drag) picks the nearest point within reach, whatever is drawn over it
        // (its label, its error bar).
        QCustomPlot& plot = panel->plot();
        connect(&plot, &QCustomPlot::mousePress, this,
                [this](QMouseEvent* e) { pressedAt_ = e->position(); });
        connect(&plot, &QCustomPlot::mouseRelease, this,
                [this, &plot, following = following](QMouseEvent* e) {
                    if ((e->position() - pressedAt_).manhattanLength() <= 4)
                        pickAt(plot, following, e->position());
                });
    }
    connect(runPicked_, &QPushButton::clicked, this, [this] {
        if (picked_) emit settingRequested(*picked_);
    });
    connect(runStandard_, &QPushButton::clicked, this, &SweepsTab::standardSweepsRequested);
}

void SweepsTab::showRun(const RunResult& r, bool analysis) {
    // A run of an experiment without a "sweeps" section is offered the standard ones.
    runStandard_->setVisible(!analysis && !r.spec.sweeps.any());
    if (r.sweeps.empty()) {  // following alone keeps the sweeps shown
        if (perceptionRows_.empty() && followingRows_.empty() && runStandard_->isVisibleTo(this))
            pickedLabel_->setText(tr("%1 has no sweeps: run the standard ones on it, or open "
                                     "experiments/accuracy_vs_time.json.")
                                      .arg(QString::fromStdString(r.spec.name)));
        return;
    }
    runPicked_->show();
    if (analysis)
        for (PlotPanel* p : {perception_, following_})
            p->setEmptyHint(
                tr("This sweep takes new taps and follows contours on simulated "
                   "rigs: run the experiment to measure it. An analysed or replayed "
                   "recording measures only the compute sweep (c), on its own taps."));
    perceptionRows_ = r.sweeps.perception;
    followingRows_ = r.sweeps.following;
    shownFollowing_ = r.spec.following;
    picked_.reset();
    runPicked_->setEnabled(false);
    pickedLabel_->setText(tr("Click a point of (a) or (b) to see its setting."));
    buildPerceptionSweepFigure(perception_->plot(), r);
    buildFollowingSweepFigure(following_->plot(), r);
    buildComputeSweepFigure(compute_->plot(), r);
    for (auto* p : {perception_, following_, compute_}) p->plot().replot();
}

void SweepsTab::showSeeds(const SweepRates& rates) {
    if (rates.empty()) return;
    buildPerceptionSweepOverSeedsFigure(perceptionSeeds_->plot(), rates);
    buildFollowingParetoFigure(pareto_->plot(), rates);
    for (auto* p : {perceptionSeeds_, pareto_}) p->plot().replot();
}

void SweepsTab::pickAt(QCustomPlot& plot, bool following, QPointF at) {
    constexpr double kReach_px = 12.0;
    int best = -1;
    double bestDistance = kReach_px;
    for (int i = 0; i < plot.graphCount(); ++i) {
        QCPGraph* g = plot.graph(i);
        const QVariantList rows = g->property(kSweepRowsProperty).toList();
        if (rows.isEmpty() || !g->keyAxis()->axisRect()->rect().contains(at.toPoint())) continue;
        int k = 0;
        for (auto it = g->data()->constBegin(); it != g->data()->constEnd() && k < rows.size();
             ++it, ++k) {
            if (!std::isfinite(it->value)) continue;
            const QPointF p(g->keyAxis()->coordToPixel(it->key),
                            g->valueAxis()->coordToPixel(it->value));
            const double d = std::hypot(p.x() - at.x(), p.y() - at.y());
            if (d < bestDistance) {
                bestDistance = d;
                best = rows[k].toInt();
            }
        }
    }
    if (best >= 0) pick(following, best);
}

bool SweepsTab::pick(bool following, int row) {
    QString text;
    SweepSetting s{shownFollowing_.followStep_mm, shownFollowing_.repositionStep_mm, 0.0};
    if (following) {
        if (row < 0 || row >= int(followingRows_.size())) return false;
        const FollowingSweepRow& f = followingRows_[std::size_t(row)];
        s = {f.followStep_mm,
             f.mode == FollowingMode::Active ? f.repositionStep_mm
                                             : shownFollowing_.repositionStep_mm,
             f.beliefThreshold};
        text = tr("%1, follow %2 mm, reposition %3 mm, %4: %5/%6 trials completed, %7 s robot "
                  "time per trial, taps %8 mm from the contour")
                   .arg(f.mode == FollowingMode::Active ? tr("active") : tr("passive"))
                   .arg(f.followStep_mm)
                   .arg(f.repositionStep_mm)
                   .arg(f.beliefThreshold > 0 ? tr("belief threshold %1").arg(f.beliefThreshold)
                                              : tr("single tap"))
                   .arg(f.completed)
                   .arg(f.trials)
                   .arg(f.meanRobotTime_s, 0, 'f', 0)
                   .arg(f.meanContourDistance_mm, 0, 'f', 2);
        if (f.paperSetting) text += tr(" (the paper's setting)");
    } else {
        if (row < 0 || row >= int(perceptionRows_.size())) return false;
        const PerceptionSweepRow& a = perceptionRows_[std::size_t(row)];
        s.beliefThreshold = a.threshold;
        text = tr("belief threshold %1: %2 taps (%3-%4) and %5 s per decision; edge angle error "
                  "%6° (%7-%8), position error %9 mm (%10-%11)")
                   .arg(a.threshold)
                   .arg(a.meanTaps, 0, 'f', 2)
                   .arg(a.taps.low, 0, 'f', 2)
                   .arg(a.taps.high, 0, 'f', 2)
                   .arg(a.meanRobotTime_s, 0, 'f', 1)
                   .arg(a.angleError_deg, 0, 'f', 1)
                   .arg(a.angle_deg.low, 0, 'f', 1)
                   .arg(a.angle_deg.high, 0, 'f', 1)
                   .arg(a.positionError_mm, 0, 'f', 2)
                   .arg(a.position_mm.low, 0, 'f', 2)
                   .arg(a.position_mm.high, 0, 'f', 2);
    }
    picked_ = s;
    pickedLabel_->setText(text);
    runPicked_->setEnabled(true);
    return true;
}

QString SweepsTab::pickedText() const {
    return pickedLabel_->text();
}

}  // namespace activetouch
