#pragma once
// The window's result tabs that show a finished run as figures (docs/window.md): training and
// validation (Figures 5 and 6), recognition (Figure 9 with each rule's confusion) and accuracy
// versus time (the three sweeps). Each builds its own widgets and redraws from a RunResult.
#include <QPointF>
#include <QSplitter>
#include <QString>
#include <QTabWidget>
#include <memory>
#include <optional>
#include <vector>

#include "core/control/FollowingSettings.h"
#include "core/run/SweepResults.h"

class QLabel;
class QPushButton;
class QTableWidget;
class QCustomPlot;

namespace activetouch {

struct RunResult;
struct SweepRates;
class PlotPanel;

/// Figure 6 (errors by orientation and position) and Figure 5 (taps across each edge).
class ValidationTab : public QTabWidget {
    Q_OBJECT
public:
    explicit ValidationTab(QWidget* parent = nullptr);
    /// Redraws from `r`; a following-only run (no taps) keeps the figures shown. Figure 6 is
    /// drawn again for the shape it is exported at.
    void showRun(const std::shared_ptr<const RunResult>& r);
    PlotPanel* tapsPanel() const { return taps_; }
    PlotPanel* errorsPanel() const { return errors_; }
    PlotPanel* continuousPanel() const { return continuous_; }

private:
    PlotPanel *taps_, *errors_, *continuous_;
};

/// Figure 9 (the traced paths' histograms against the templates) over the confusion of each
/// rule: a row per shape traced, a column per shape named.
class RecognitionTab : public QSplitter {
    Q_OBJECT
public:
    explicit RecognitionTab(QWidget* parent = nullptr);
    void showRun(const RunResult& r);
    PlotPanel* panel() const { return figure_; }

private:
    PlotPanel* figure_;
    QTableWidget *raw_, *smoothed_;
    QLabel *rawTitle_, *smoothedTitle_;
};

/// A following setting picked from a sweep's point, to run.
struct SweepSetting {
    double followStep_mm = 2.0, repositionStep_mm = 1.0, beliefThreshold = 0.0;
};

/// The accuracy-versus-time sweeps: (a) taps per decision, (b) following steps, (c) compute.
/// Clicking a point of (a) or (b) shows its setting and what it measured, with a button that
/// follows with that setting; a run that measured no sweeps is offered the standard ones.
class SweepsTab : public QWidget {
    Q_OBJECT
public:
    explicit SweepsTab(QWidget* parent = nullptr);
    /// Redraws from `r` if it measured sweeps; `analysis`: a recording was analysed, which
    /// measures only the compute sweep. A run without sweeps of an experiment without a
    /// "sweeps" section offers the standard sweeps on it.
    void showRun(const RunResult& r, bool analysis);
    PlotPanel* perceptionPanel() const { return perception_; }
    PlotPanel* followingPanel() const { return following_; }
    PlotPanel* computePanel() const { return compute_; }
    /// Shows sweeps (a) and (b) over the seeds of a seeds run, if its runs measured them.
    void showSeeds(const SweepRates& rates);
    PlotPanel* perceptionOverSeedsPanel() const { return perceptionSeeds_; }
    PlotPanel* paretoOverSeedsPanel() const { return pareto_; }
    /// Picks row `row` of the shown sweep (a) (`following` false) or (b), as a click on its
    /// point does; false if there is no such row.
    bool pick(bool following, int row);
    /// The picked setting, if a point was picked since the last run was shown.
    const std::optional<SweepSetting>& picked() const { return picked_; }
    QString pickedText() const;

signals:
    /// Follow with this setting (the protocol's other values as shown).
    void settingRequested(const SweepSetting& setting);
    /// Run the standard sweeps on the experiment shown.
    void standardSweepsRequested();

private:
    /// Picks the point of the plot's sweep series nearest `at` (pixels), if one is near.
    void pickAt(QCustomPlot& plot, bool following, QPointF at);
    QPointF pressedAt_;
    QTabWidget* tabs_;
    PlotPanel *perception_, *following_, *compute_, *perceptionSeeds_, *pareto_;
    QLabel* pickedLabel_;
    QPushButton *runPicked_, *runStandard_;
    std::vector<PerceptionSweepRow> perceptionRows_;
    std::vector<FollowingSweepRow> followingRows_;
    FollowingSettings shownFollowing_;
    std::optional<SweepSetting> picked_;
};

}  // namespace activetouch
