#pragma once
// The window's result tabs that show a finished run as figures (docs/window.md): training and
// validation (Figures 5 and 6), recognition (Figure 9 with each rule's confusion) and accuracy
// versus time (the three sweeps). Each builds its own widgets and redraws from a RunResult.
#include <QSplitter>
#include <QString>
#include <QTabWidget>
#include <memory>

class QLabel;
class QTableWidget;

namespace activetouch {

struct RunResult;
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

/// The accuracy-versus-time sweeps: (a) taps per decision, (b) following steps, (c) compute.
class SweepsTab : public QTabWidget {
    Q_OBJECT
public:
    explicit SweepsTab(QWidget* parent = nullptr);
    /// Redraws from `r` if it measured sweeps; `analysis`: a recording was analysed, which
    /// measures only the compute sweep.
    void showRun(const RunResult& r, bool analysis);
    PlotPanel* perceptionPanel() const { return perception_; }
    PlotPanel* followingPanel() const { return following_; }
    PlotPanel* computePanel() const { return compute_; }

private:
    PlotPanel *perception_, *following_, *compute_;
};

}  // namespace activetouch
