#include "app/gui/ResultTabs.h"

#include <QColor>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>
#include <tuple>

#include "app/figures/FollowingFigures.h"
#include "app/figures/SweepFigures.h"
#include "app/figures/ValidationFigures.h"
#include "app/gui/PlotPanel.h"
#include "core/run/SeedRates.h"
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
            if (a != b && count > 0) cell->setBackground(QColor(255, 220, 200));
            table->setItem(a, b, cell);
        }
    // The shapes' names whole: columns as wide as their names, never elided.
    table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    table->verticalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    table->setTextElideMode(Qt::ElideNone);
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
        column->addWidget(*title);
        column->addWidget(*table, 1);
        confusionRow->addLayout(column, 1);
    }
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

SweepsTab::SweepsTab(QWidget* parent) : QTabWidget(parent) {
    perception_ = new PlotPanel("sweep_a_sequential_perception");
    following_ = new PlotPanel("sweep_b_following");
    compute_ = new PlotPanel("sweep_c_compute");
    addTab(perception_, tr("(a) taps per decision"));
    addTab(following_, tr("(b) following steps"));
    addTab(compute_, tr("(c) compute"));
    setToolTip(tr("Run an experiment with sweeps, such as experiments/accuracy_vs_time.json"));
    for (PlotPanel* p : {perception_, following_, compute_})
        p->setEmptyHint(
            tr("No sweeps measured yet. Open experiments/accuracy_vs_time.json (or any "
               "experiment with a \"sweeps\" section) and click Run whole protocol "
               "to measure what accuracy costs in time."));
}

void SweepsTab::showRun(const RunResult& r, bool analysis) {
    if (r.sweeps.empty()) return;
    if (analysis)
        for (PlotPanel* p : {perception_, following_})
            p->setEmptyHint(
                tr("This sweep takes new taps and follows contours on simulated "
                   "rigs: run the experiment to measure it. An analysed or replayed "
                   "recording measures only the compute sweep (c), on its own taps."));
    buildPerceptionSweepFigure(perception_->plot(), r);
    buildFollowingSweepFigure(following_->plot(), r);
    buildComputeSweepFigure(compute_->plot(), r);
    for (auto* p : {perception_, following_, compute_}) p->plot().replot();
}

}  // namespace activetouch
