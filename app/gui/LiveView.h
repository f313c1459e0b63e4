#pragma once
// The live tab (docs/window.md): the fingertip with its 12 taxels at their places, coloured by
// pressure on a fixed scale, beside 12 taxel bars (each in the taxel's own colour) with numeric
// readouts, updated at 50 Hz; the total pressure of the last seconds against the contact
// threshold; the last tap's 50-sample traces; the stage position; and, while following, the
// percept; and the taxel scope, every channel over the last seconds (TaxelScope). A GUI timer
// draws the newest state from the LiveFeed; data never drives a replot. A
// frame redraws the bars' own layer alone, and nothing is drawn while the tab is hidden. Pause
// holds what is shown (the run goes on); Resume shows the newest state again.
#include <QElapsedTimer>
#include <QLabel>
#include <QTimer>
#include <QWidget>

#include "app/gui/LiveFeed.h"
#include "core/fingertip/FingertipSpec.h"

class QCPBars;
class QCPLayer;
class QCPItemText;
class QPushButton;

class QGridLayout;

namespace activetouch {

class FingertipView;
class PlotPanel;
class TaxelScope;

class LiveView : public QWidget {
    Q_OBJECT
public:
    LiveView(LiveFeed& feed, QWidget* parent = nullptr);

    PlotPanel* barsPanel() const { return bars_; }
    PlotPanel* tracesPanel() const { return traces_; }
    FingertipView* fingertipView() const { return fingertip_; }
    TaxelScope* scope() const { return scope_; }
    /// Frames drawn so far (for tests and the CPU benchmark); none while the view is hidden.
    std::uint64_t framesDrawn() const { return framesDrawn_; }

    /// The fingertip the view draws and the reflex's contact threshold (from the scene).
    void setFingertip(const FingertipSpec& fingertip, double contactThreshold);
    bool paused() const { return paused_; }
    void setPaused(bool paused);
    /// What the percept line says now (empty while no following tap has been shown).
    QString perceptText() const { return percept_->isVisible() ? percept_->text() : QString(); }
    QString tapText() const { return tap_->text(); }

signals:
    void pausedChanged(bool paused);

private:
    /// The constructor's parts: the stage, tap and percept read-outs with the pause button; the
    /// live taxel bars; the last tap's traces.
    QGridLayout* buildReadouts();
    void buildBars();
    void buildTraces();
    void tick();
    /// Takes the newest tap and frame from the feed into the plots' data; whether the bars changed.
    bool takeNewest();
    LiveFeed& feed_;
    PlotPanel* bars_;
    PlotPanel* traces_;
    FingertipView* fingertip_;
    TaxelScope* scope_;
    QElapsedTimer clock_;  ///< the scope's time axis: seconds since the view was made
    QCPLayer* liveLayer_ = nullptr;
    std::vector<QCPBars*> barPlottables_;  ///< one per taxel, in its colour
    std::vector<QCPItemText*> readouts_;
    QLabel* pose_;
    QLabel* tap_;
    QLabel* percept_;
    QPushButton* pause_;
    QTimer timer_;
    std::uint64_t shownTap_ = 0, shownFrame_ = 0, framesDrawn_ = 0;
    bool undrawn_ = false;  // the bars' data changed since they were last drawn
    bool paused_ = false;
    int playback_ = 0;  // frame of the newest tap being replayed when frames are not streamed
};

}  // namespace activetouch
