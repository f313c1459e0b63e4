#pragma once
// The contour following tab (docs/window.md): active and passive paths side by side over the
// outline, per-trial statistics, and a step-by-step replay of one trial with the percept and the
// rule that fired at each tap.
#include <QTimer>
#include <QWidget>
#include <memory>

class QComboBox;
class QPushButton;
class QLabel;
class QSlider;
class QTableWidget;
class QCPCurve;
class QCPItemTracer;

namespace activetouch {

struct RunResult;
class PlotPanel;

class FollowingTab : public QWidget {
    Q_OBJECT
public:
    explicit FollowingTab(QWidget* parent = nullptr);
    void showRun(std::shared_ptr<const RunResult> result);

    PlotPanel* activePanel() const { return active_; }
    PlotPanel* passivePanel() const { return passive_; }
    PlotPanel* replayPanel() const { return replay_; }
    /// Replays trial `index` (in the table's order) at tap `tap`.
    void replay(int index, int tap);
    QString replayText() const;
    /// The trial (in the table's order) and tap the replay shows.
    int replayedTrial() const;
    int replayedTap() const;
    /// Plays the replay on from the tap shown, 20 taps a second, to the trial's last tap.
    void play();
    void pause();
    bool playing() const { return player_.isActive(); }

private:
    std::shared_ptr<const RunResult> result_;
    PlotPanel *active_, *passive_, *replay_;
    QTableWidget* table_;
    QComboBox* trial_;
    QSlider* slider_;
    QPushButton* play_;
    QTimer player_;
    QLabel* step_;
};

}  // namespace activetouch
