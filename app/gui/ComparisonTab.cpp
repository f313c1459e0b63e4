#include "app/gui/ComparisonTab.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>

#include "app/figures/ComparisonFigures.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/SeedRange.h"
#include "qcustomplot.h"

namespace activetouch {

ComparisonTab::ComparisonTab(QWidget* parent) : QWidget(parent) {
    auto* layout = new QVBoxLayout(this);
    compare_ = new QPushButton(tr("Compare with..."));
    compare_->setObjectName("compareWith");
    compare_->setEnabled(false);
    compare_->setToolTip(
        tr("Choose another experiment file (B) to run beside the experiment as "
           "shown (A) on the same seeds"));
    connect(compare_, &QPushButton::clicked, this,
            [this] { emit compareRequested(seeds_->first(), seeds_->last()); });
    seeds_ = new SeedRangeBar(
        "compareFirstSeed", "compareLastSeed", 100, compare_,
        tr("A seed gives both experiments the same data sets and the same noise on each trial, "
           "so where they differ in a setting, the trials they end differently show its effect "
           "(McNemar's test), more surely than two rates with overlapping intervals."));
    layout->addWidget(seeds_);

    summary_ = new SummaryTable("comparisonSummary",
                                tr("Compare the experiment as shown with another experiment "
                                   "file over a range of seeds."));
    summary_->setColumns({tr("outcome"), tr("A"), tr("B"), tr("only A"), tr("only B"),
                          tr("B − A (95 % interval)"), tr("McNemar p")});
    layout->addWidget(summary_);
    table_ = new QTableWidget(0, 6);
    table_->setObjectName("comparisonTrials");
    table_->setHorizontalHeaderLabels(
        {tr("seed"), tr("mode"), tr("label"), tr("trial"), tr("A ended"), tr("B ended")});
    for (int c = 0; c < 4; ++c)
        table_->horizontalHeader()->setSectionResizeMode(c, QHeaderView::ResizeToContents);
    table_->horizontalHeader()->setSectionResizeMode(4, QHeaderView::Stretch);
    table_->horizontalHeader()->setSectionResizeMode(5, QHeaderView::Stretch);
    table_->setWordWrap(false);
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table_->verticalHeader()->setVisible(false);
    connect(table_, &QTableWidget::itemSelectionChanged, this, [this] { updatePairButton(); });
    connect(table_, &QTableWidget::cellDoubleClicked, this,
            [this](int row, int) { requestPair(row); });
    showPair_ = new QPushButton(tr("Show the trial in both"));
    showPair_->setObjectName("showTrialPair");
    showPair_->setEnabled(false);
    showPair_->setToolTip(
        tr("Run the selected row's seed in both experiments and draw that "
           "trial's two paths on its object"));
    connect(showPair_, &QPushButton::clicked, this, [this] { requestPair(table_->currentRow()); });
    pair_ = new PlotPanel("compare_trial_pair");
    pair_->setEmptyHint(
        tr("Double-click a trial above, or select it and click Show the trial in both: that "
           "seed runs again in both experiments and the trial's two paths are drawn here."));
    // The trials take the left column's height; the differences and the trial in both share
    // the right one as two tabs (showing a trial brings its tab forward).
    auto* left = new QWidget;
    auto* tableLayout = new QVBoxLayout(left);
    tableLayout->setContentsMargins(0, 0, 0, 0);
    tableLayout->addWidget(table_, 1);
    tableLayout->addWidget(showPair_, 0, Qt::AlignLeft);

    plot_ = new PlotPanel("compare");
    plot_->setEmptyHint(
        tr("Choose the seeds above and click Compare with...: each part of the "
           "result's difference between the two experiments appears here with "
           "its interval."));
    figures_ = new QTabWidget;
    figures_->setObjectName("comparisonFigures");
    figures_->addTab(plot_, tr("Differences"));
    figures_->addTab(pair_, tr("The trial in both"));
    auto* split = new QSplitter(Qt::Horizontal);
    split->addWidget(left);
    split->addWidget(figures_);
    split->setSizes({560, 840});
    layout->addWidget(split, 1);
}

void ComparisonTab::setRunnable(bool runnable) {
    runnable_ = runnable;
    compare_->setEnabled(runnable && !running_);
    updatePairButton();
}

void ComparisonTab::updatePairButton() {
    showPair_->setEnabled(runnable_ && !running_ && table_->currentRow() >= 0 &&
                          !table_->selectedItems().isEmpty());
}

void ComparisonTab::requestPair(int row) {
    if (!runnable_ || running_ || row < 0 || row >= table_->rowCount()) return;
    emit trialPairRequested(
        table_->item(row, 0)->text().toULongLong(),
        static_cast<FollowingMode>(table_->item(row, 1)->data(Qt::UserRole).toInt()),
        table_->item(row, 2)->text(), table_->item(row, 3)->text().toInt());
}

void ComparisonTab::showTrialPair(const TrialPairRun& pair) {
    buildTrialPairFigure(pair_->plot(), pair);
    pair_->requestReplot();
    figures_->setCurrentWidget(pair_);
}

void ComparisonTab::begin(const QString& a, const QString& b, std::uint64_t first,
                          std::uint64_t last) {
    seeds_->set(first, last);
    running_ = true;
    seedsPlanned_ = static_cast<int>(last - first + 1);
    compare_->setEnabled(false);
    figures_->setCurrentWidget(plot_);
    table_->setRowCount(0);
    updatePairButton();
    pair_->plot().clearItems();
    pair_->plot().clearPlottables();
    pair_->requestReplot();
    plot_->plot().clearItems();
    plot_->plot().clearPlottables();
    plot_->requestReplot();
    summaryText_ = tr("A = %1, B = %2: running...").arg(a, b);
    summary_->setState(summaryText_);
    summary_->clearRows();
}

void ComparisonTab::addSeed(std::uint64_t seed, const std::vector<PairedTrial>& pairs,
                            const PairedComparison& soFar) {
    auto ended = [](const std::string& outcome, const std::string& named) {
        return QString::fromStdString(endedText(outcome, named));
    };
    for (const PairedTrial& p : pairs) {
        if (!p.differs()) continue;
        const int row = table_->rowCount();
        table_->insertRow(row);
        table_->setItem(row, 0, new QTableWidgetItem(QString::number(seed)));
        auto* mode = new QTableWidgetItem(modeName(p.mode));
        mode->setData(Qt::UserRole, static_cast<int>(p.mode));
        table_->setItem(row, 1, mode);
        table_->setItem(row, 2, new QTableWidgetItem(QString::fromStdString(p.label)));
        table_->setItem(row, 3, new QTableWidgetItem(QString::number(p.trial)));
        // The endings are long for their columns: each cell's tooltip gives the whole of it.
        for (const auto& [column, text] : {std::pair{4, ended(p.outcomeA, p.namedA)},
                                           std::pair{5, ended(p.outcomeB, p.namedB)}}) {
            auto* item = new QTableWidgetItem(text);
            item->setToolTip(text);
            table_->setItem(row, column, item);
        }
    }
    show(soFar, tr("running: %1 of %2 seeds compared, %3 trials ended differently")
                    .arg(soFar.seeds)
                    .arg(seedsPlanned_)
                    .arg(table_->rowCount()));
}

void ComparisonTab::finish(const PairedComparison& comparison, const QString& dir, bool cancelled) {
    running_ = false;
    compare_->setEnabled(runnable_);
    updatePairButton();
    show(comparison,
         cancelled ? tr("cancelled after %1 seeds; results in %2").arg(comparison.seeds).arg(dir)
                   : tr("finished; results in %1").arg(dir));
}

void ComparisonTab::show(const PairedComparison& comparison, const QString& state) {
    QStringList lines;
    for (const std::string& line : describeComparison(comparison))
        lines << QString::fromStdString(line);
    lines << state;
    summaryText_ = lines.join('\n');
    summary_->setState(
        tr("A = %1, B = %2, %3 seeds, trial by trial; %4")
            .arg(QString::fromStdString(comparison.nameA), QString::fromStdString(comparison.nameB))
            .arg(comparison.seeds)
            .arg(state));
    summary_->clearRows();
    for (const std::string& f : comparison.failedRuns)
        summary_->addNote(tr("run failed (device or rig error), its seed not compared: %1")
                              .arg(QString::fromStdString(f)));
    auto rate = [](const Rate& x) {
        return QString("%1/%2 (%3 %)")
            .arg(x.count)
            .arg(x.total)
            .arg(100.0 * x.fraction(), 0, 'f', 1);
    };
    auto points = [](double fraction) {
        return QString("%1%2").arg(fraction >= 0 ? "+" : "").arg(100.0 * fraction, 0, 'f', 1);
    };
    for (const PairedPart& part : kPairedParts) {
        const PairedRate& r = comparison.*part.rate;
        if (r.pairs() == 0) continue;
        summary_->addRow({QString::fromUtf8(part.name), rate(r.a()), rate(r.b()),
                          QString::number(r.onlyA), QString::number(r.onlyB),
                          QString("%1 (%2 to %3) points")
                              .arg(points(r.difference()), points(r.differenceLow()),
                                   points(r.differenceHigh())),
                          QString::number(r.mcnemarP(), 'g', 3)});
    }
    summary_->addRow(
        {tr("robot time per run"),
         QString("%1 min").arg(comparison.meanRobotTimeA_s() / 60.0, 0, 'f', 0),
         QString("%1 min").arg(comparison.meanRobotTimeB_s() / 60.0, 0, 'f', 0), "", "",
         QString("%1%2 min")
             .arg(comparison.meanRobotTimeB_s() >= comparison.meanRobotTimeA_s() ? "+" : "")
             .arg((comparison.meanRobotTimeB_s() - comparison.meanRobotTimeA_s()) / 60.0, 0, 'f',
                  1),
         ""});
    if (comparison.unpairedTrials > 0)
        summary_->addNote(tr("%1 trials only one experiment has (label, mode or repeat) are not "
                             "compared")
                              .arg(comparison.unpairedTrials));
    buildComparisonFigure(plot_->plot(), comparison, /*stacked=*/true);
    plot_->requestReplot();
}

void ComparisonTab::interrupted() {
    if (!running_) return;
    running_ = false;
    compare_->setEnabled(runnable_);
    updatePairButton();
    summaryText_ += tr("\nstopped: the seeds shown are all there are");
    summary_->setState(summary_->state() + tr("; stopped: the seeds shown are all there are"));
}

QString ComparisonTab::summaryText() const {
    return summaryText_;
}

void ComparisonTab::requestComparison() {
    emit compareRequested(seeds_->first(), seeds_->last());
}

}  // namespace activetouch
