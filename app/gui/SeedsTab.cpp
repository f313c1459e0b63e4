#include "app/gui/SeedsTab.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include "app/figures/SeedFigures.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/SeedRange.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {

QTableWidgetItem* cell(const QString& text) {
    auto* item = new QTableWidgetItem(text);
    item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    return item;
}
}  // namespace

SeedsTab::SeedsTab(QWidget* parent) : QWidget(parent), plot_(new PlotPanel("seed_rates")) {
    auto* layout = new QVBoxLayout(this);
    run_ = new QPushButton(tr("Run over seeds"));
    run_->setObjectName("runSeeds");
    connect(run_, &QPushButton::clicked, this,
            [this] { emit runRequested(seeds_->first(), seeds_->last()); });
    seeds_ = new SeedRangeBar(
        "firstSeed", "lastSeed", 10, run_,
        tr("Each seed is a whole run on the simulated rig: its own data sets, training, valid "
           "range and trials. The rates, with their 95 % intervals, are what a claim rests on; "
           "an interval counts each seed as one independent run, since its trials share its "
           "training."));
    layout->addWidget(seeds_);

    auto* split = new QSplitter(Qt::Horizontal);
    auto* left = new QWidget;
    auto* ll = new QVBoxLayout(left);
    ll->setContentsMargins(0, 0, 0, 0);
    summary_ = new SummaryTable("seedsSummary",
                                tr("Run the experiment over a range of seeds to see its rates."));
    summary_->setColumns({tr("outcome"), tr("count"), tr("rate"), tr("95 % interval")});
    ll->addWidget(summary_);
    table_ = new QTableWidget(0, 9);
    table_->setHorizontalHeaderLabels(
        {tr("seed"), tr("passive\nlost"), tr("active\ncompleted"), tr("recognised\n(paper's rule)"),
         tr("recognised\n(smoothed)"), tr("angle error\n(°)"), tr("valid range\n(mm)"),
         tr("paper's result\nwhole"),
         tr("passive not lost at a corner,\nactive trials lost, paths misnamed")});
    for (int c = 0; c < 8; ++c)
        table_->horizontalHeader()->setSectionResizeMode(c, QHeaderView::ResizeToContents);
    table_->horizontalHeader()->setSectionResizeMode(8, QHeaderView::Stretch);
    // The shortfalls are read from their start, as the cells beneath are, when the column is
    // narrower than its heading.
    table_->horizontalHeaderItem(8)->setTextAlignment(Qt::AlignLeft | Qt::AlignVCenter);
    table_->setWordWrap(false);
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table_->setSelectionBehavior(QAbstractItemView::SelectRows);
    table_->setSelectionMode(QAbstractItemView::SingleSelection);
    table_->verticalHeader()->setVisible(false);
    ll->addWidget(table_, 1);
    runSeed_ = new QPushButton(tr("Run the selected seed"));
    runSeed_->setObjectName("runSelectedSeed");
    runSeed_->setToolTip(
        tr("Runs that seed once more as a whole run (the same run, tap for tap) and shows its "
           "trials in the Contour following tab, opening the replay on its first lost active "
           "trial. Double-clicking a row does the same."));
    ll->addWidget(runSeed_, 0, Qt::AlignLeft);
    connect(runSeed_, &QPushButton::clicked, this, [this] {
        if (const auto seed = selectedSeed()) emit seedRunRequested(*seed);
    });
    connect(table_, &QTableWidget::cellDoubleClicked, this, [this](int row, int) {
        if (!runnable_ || !table_->item(row, 0)) return;
        emit seedRunRequested(table_->item(row, 0)->text().toULongLong());
    });
    connect(table_, &QTableWidget::itemSelectionChanged, this, &SeedsTab::updateSeedButton);
    split->addWidget(left);
    split->addWidget(plot_);
    plot_->setEmptyHint(
        tr("Choose the seeds above and click Run over seeds: each seed adds its "
           "outcome here, with the rates so far and their intervals."));
    // The rates' lines (about 90 characters) first; the figure takes the rest.
    split->setStretchFactor(0, 1);
    split->setStretchFactor(1, 1);
    split->setSizes({760, 640});
    layout->addWidget(split, 1);
}

void SeedsTab::setRunnable(bool runnable) {
    runnable_ = runnable;
    run_->setEnabled(runnable);
    updateSeedButton();
}

std::optional<std::uint64_t> SeedsTab::selectedSeed() const {
    const QList<QTableWidgetItem*> selected = table_->selectedItems();
    if (selected.isEmpty()) return std::nullopt;
    const QTableWidgetItem* seed = table_->item(selected.first()->row(), 0);
    if (!seed) return std::nullopt;
    return seed->text().toULongLong();
}

std::optional<std::uint64_t> SeedsTab::firstSeedWithLostActiveTrial() const {
    for (const SeedOutcome& o : rates_.seeds)
        if (o.activeCompleted < o.activeTrials) return o.seed;
    return std::nullopt;
}

void SeedsTab::updateSeedButton() {
    runSeed_->setEnabled(runnable_ && selectedSeed().has_value());
}

void SeedsTab::begin(const QString& experiment) {
    experiment_ = experiment;
    rates_ = {};
    running_ = true;
    table_->setRowCount(0);
    updateSeedButton();
    buildSeedRatesFigure(plot_->plot(), rates_, experiment_, true);
    plot_->requestReplot();
    showSummary(tr("running"));
}

void SeedsTab::addSeed(const SeedOutcome& o) {
    rates_.seeds.push_back(o);
    const int row = table_->rowCount();
    table_->insertRow(row);
    auto fraction = [](int count, int total) {
        return total > 0 ? QString("%1 / %2").arg(count).arg(total) : QString("-");
    };
    // The passive trials not lost at a corner, the active trials lost, then the paths misnamed.
    QStringList shortfalls;
    if (o.failed())  // a device or rig error: the run failed, its later trials were not run
        shortfalls << tr("run failed (%1 trials not run): %2")
                          .arg(o.trialsNotRun)
                          .arg(QString::fromStdString(o.runFailure));
    for (const auto& f : o.passiveShortfalls) shortfalls << QString::fromStdString(f);
    for (const auto& f : o.failures) shortfalls << QString::fromStdString(f);
    for (const auto& m : o.misnamed()) shortfalls << QString::fromStdString(m);
    table_->setItem(row, 0, cell(QString::number(o.seed)));
    QString passive = fraction(o.passiveLost, o.passiveTrials);
    if (o.passiveLostAtCorner() < o.passiveLost)
        passive += tr(" (%1 at a corner)").arg(o.passiveLostAtCorner());
    table_->setItem(row, 1, cell(passive));
    table_->setItem(row, 2, cell(fraction(o.activeCompleted, o.activeTrials)));
    table_->setItem(row, 3, cell(fraction(o.recognisedRaw(), o.recognitionTrials())));
    table_->setItem(row, 4, cell(fraction(o.recognisedSmoothed(), o.recognitionTrials())));
    table_->setItem(row, 5, cell(QString::number(o.angleError_deg, 'f', 2)));
    table_->setItem(row, 6, cell(QString::fromStdString(o.validRange.span())));
    table_->setItem(row, 7,
                    cell(!o.paperResultApplies() ? QString("-")
                         : o.paperResult()       ? tr("yes")
                                                 : tr("no")));
    auto* shortfall = new QTableWidgetItem(shortfalls.join("; "));
    shortfall->setToolTip(shortfalls.join("\n"));
    table_->setItem(row, 8, shortfall);
    // A run that failed on a device is grey; one that lost an active trial red; one that only
    // misnamed a path (paper's rule), amber.
    const bool lostActive = o.activeCompleted < o.activeTrials,
               misnamedRaw = o.recognisedRaw() < o.recognitionTrials();
    if (o.failed() || lostActive || misnamedRaw)
        for (int c = 0; c < table_->columnCount(); ++c) {
            table_->item(row, c)->setBackground(o.failed()   ? QColor(225, 225, 225)
                                                : lostActive ? QColor(255, 235, 230)
                                                             : QColor(255, 246, 214));
            table_->item(row, c)->setForeground(QColor(Qt::black));  // read in a dark theme too
        }
    table_->scrollToBottom();
    buildSeedRatesFigure(plot_->plot(), rates_, experiment_, true);
    plot_->requestReplot();
    showSummary(tr("running"));
}

void SeedsTab::finish(const QString& dir, bool cancelled) {
    running_ = false;
    showSummary((cancelled ? tr("cancelled after %1 seeds") : tr("finished, %1 seeds"))
                    .arg(rates_.seeds.size()) +
                tr("\nresults in %1").arg(dir));
}

void SeedsTab::interrupted() {
    if (!running_) return;
    running_ = false;
    showSummary(tr("stopped after %1 seeds (see the log)").arg(rates_.seeds.size()));
}

QString SeedsTab::summaryText() const {
    return summaryText_;
}

void SeedsTab::showSummary(const QString& state) {
    QStringList lines{QString("%1 - %2").arg(experiment_, state)};
    for (const std::string& line : describeRates(rates_)) lines << QString::fromStdString(line);
    summaryText_ = lines.join('\n');
    summary_->setState(lines.front());
    summary_->clearRows();
    for (const ReportRow& row : rateReport(rates_)) {
        const QString what = QString::fromStdString(row.what);
        if (!row.rate) {
            summary_->addNote(what, row.indent);
        } else if (row.rate->total == 0) {
            summary_->addRow({what, tr("none in this experiment")}, row.indent);
        } else {
            const Rate& r = *row.rate;
            summary_->addRow({what, QString("%1 / %2").arg(r.count).arg(r.total),
                              QString("%1 %").arg(100.0 * r.fraction(), 0, 'f', 1),
                              QString("%1–%2 %")
                                  .arg(100.0 * r.low(), 0, 'f', 1)
                                  .arg(100.0 * r.high(), 0, 'f', 1)},
                             row.indent);
        }
    }
}

void SeedsTab::requestRun() {
    emit runRequested(seeds_->first(), seeds_->last());
}

}  // namespace activetouch
