#pragma once
// The rates-over-seeds tab: runs the experiment once per seed (each a whole run on the simulated
// rig: its own data sets, training, valid range and trials) and shows each seed's outcome as it
// finishes, the rates with their 95 % intervals, and how they settle as seeds accumulate.
#include <QWidget>
#include <cstdint>
#include <memory>
#include <optional>

#include "core/analysis/SeedRates.h"

class QLabel;
class QPushButton;
class QTableWidget;

namespace activetouch {

class PlotPanel;
class SeedRangeBar;
class SummaryTable;

class SeedsTab : public QWidget {
    Q_OBJECT
public:
    explicit SeedsTab(QWidget* parent = nullptr);

    /// Enables the run buttons (an experiment is open and nothing is running).
    void setRunnable(bool runnable);
    /// Asks for a run over the seeds the range shows (the Run menu).
    void requestRun();
    /// The seed of the table's selected row, if a row is selected.
    std::optional<std::uint64_t> selectedSeed() const;
    /// The first seed shown that lost an active trial, if any.
    std::optional<std::uint64_t> firstSeedWithLostActiveTrial() const;

    /// Empties the table and plot for a new seeds run of `experiment`.
    void begin(const QString& experiment);
    /// Adds a finished seed: a table row, the summary and the plot follow.
    void addSeed(const SeedOutcome& outcome);
    /// The run has ended (every finished seed has been added); `dir` holds its files.
    void finish(const QString& dir, bool cancelled);
    /// The run stopped on an error: the seeds shown are all there will be.
    void interrupted();

    const QString& experiment() const { return experiment_; }
    PlotPanel* ratesPanel() const { return plot_; }
    QTableWidget* table() const { return table_; }
    QString summaryText() const;

signals:
    void runRequested(std::uint64_t first, std::uint64_t last);
    /// Asks for one seed's whole run, to look at its trials (a double-click on its row, or the
    /// button under the table).
    void seedRunRequested(std::uint64_t seed);

private:
    void showSummary(const QString& state);
    void updateSeedButton();

    QString experiment_;
    bool running_ = false;
    bool runnable_ = false;
    SeedRates rates_;
    SeedRangeBar* seeds_;
    QPushButton *run_, *runSeed_;
    QTableWidget* table_;
    SummaryTable* summary_;
    QString summaryText_;
    PlotPanel* plot_;
};

}  // namespace activetouch
