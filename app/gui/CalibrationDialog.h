#pragma once
// The window's Calibrate action (docs/calibration.md): fits a scene to a recording of training and
// test taps off the window's thread, then shows every estimate with its interval, which effects
// the taps call for and why, each taxel's recorded readings against the fitted scene's, and
// Figure 6 recorded beside simulated; the fitted scene can be saved.
#include <QDialog>
#include <atomic>
#include <memory>
#include <thread>

#include "core/experiment/Experiment.h"
#include "devices/simulated/SceneFit.h"

class QLabel;
class QPushButton;
class QTableWidget;
class QCustomPlot;

namespace activetouch {

class CalibrationDialog : public QDialog {
    Q_OBJECT
public:
    /// Starts fitting `spec`'s scene to the taps recorded in `recording` (a taps.csv); a recording
    /// that cannot be read is said in the dialog, and nothing is fitted.
    CalibrationDialog(const ExperimentSpec& spec, const QString& recording, QWidget* parent);
    ~CalibrationDialog() override;

    bool finished() const { return done_; }
    const SceneFit* fit() const { return fit_.get(); }
    /// Writes the fitted scene to `path` whole; returns an empty string or why it could not.
    QString saveFittedScene(const QString& path);

    QTableWidget* estimatesTable() const { return estimates_; }
    QTableWidget* choicesTable() const { return choices_; }
    QTableWidget* taxelsTable() const { return taxels_; }

signals:
    void fitFinished(bool ok);

private:
    /// Starts the fit on its own thread; showFit() gets its result.
    void startFit();
    void showFit(std::shared_ptr<SceneFit> fit, std::shared_ptr<Figure6Comparison> figure6,
                 const QString& problem);

    ExperimentSpec spec_;
    QString recording_;
    QLabel* status_ = nullptr;
    QTableWidget *estimates_ = nullptr, *choices_ = nullptr, *taxels_ = nullptr;
    QCustomPlot* plot_ = nullptr;
    QPushButton* save_ = nullptr;
    std::shared_ptr<SceneFit> fit_;
    std::thread worker_;
    std::shared_ptr<std::atomic<bool>> alive_ = std::make_shared<std::atomic<bool>>(true);
    bool done_ = false;
};

}  // namespace activetouch
