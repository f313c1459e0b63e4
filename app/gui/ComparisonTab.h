#pragma once
// The comparison tab: the experiment as shown (A) against another experiment file (B), run on
// the same seeds and compared trial by trial (core/analysis/PairedComparison.h). Each seed's trials
// that the two ended differently arrive as rows as it finishes, and each outcome's rate in A and
// in B, the disagreements, the paired difference with its interval and McNemar's p follow the
// seeds as they accumulate.
#include <QWidget>
#include <cstdint>
#include <vector>

#include "core/analysis/PairedComparison.h"

class QLabel;
class QPushButton;
class QTableWidget;
class QTabWidget;

namespace activetouch {

class SummaryTable;

class PlotPanel;
class SeedRangeBar;

class ComparisonTab : public QWidget {
    Q_OBJECT
public:
    explicit ComparisonTab(QWidget* parent = nullptr);

    /// Enables the compare button (an experiment is open and nothing is running).
    void setRunnable(bool runnable);
    /// Asks for a comparison over the seeds the range shows (the Run menu).
    void requestComparison();

    /// Empties the table for a comparison of `a` against `b` over the seeds `first` to `last`
    /// (which the seed boxes then show).
    void begin(const QString& a, const QString& b, std::uint64_t first, std::uint64_t last);
    /// Adds a finished seed: a row for each trial the two ended differently; the summary and the
    /// figure show the comparison so far.
    void addSeed(std::uint64_t seed, const std::vector<PairedTrial>& pairs,
                 const PairedComparison& soFar);
    /// The comparison has ended; `dir` holds its files.
    void finish(const PairedComparison& comparison, const QString& dir, bool cancelled);
    /// The comparison stopped on an error: the seeds shown are all there will be.
    void interrupted();

    /// Shows one trial as A and B ran it (asked for with trialPairRequested).
    void showTrialPair(const TrialPairRun& pair);

    QTableWidget* table() const { return table_; }
    PlotPanel* plotPanel() const { return plot_; }
    /// The trial pair shown under the table.
    PlotPanel* pairPanel() const { return pair_; }
    QString summaryText() const;

signals:
    /// Asks to choose experiment B and compare over the seeds first..last.
    void compareRequested(std::uint64_t first, std::uint64_t last);
    /// Asks to run the trial of the selected row in both experiments (a double-click on the row,
    /// or the button under the table).
    void trialPairRequested(quint64 seed, activetouch::FollowingMode mode, const QString& label,
                            int trial);

private:
    void show(const PairedComparison& comparison, const QString& state);
    void updatePairButton();
    /// Asks for the trial pair of `row`.
    void requestPair(int row);

    bool running_ = false, runnable_ = false;
    int seedsPlanned_ = 0;
    SeedRangeBar* seeds_;
    QPushButton *compare_, *showPair_;
    SummaryTable* summary_;
    QString summaryText_;
    QTableWidget* table_;
    PlotPanel *plot_, *pair_;
    QTabWidget* figures_;  ///< the differences and the trial in both
};

}  // namespace activetouch
