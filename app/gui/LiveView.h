#pragma once
// The live tab (docs/window.md): 12 taxel bars on a fixed 0-255 scale with numeric readouts,
// updated at 50 Hz; the last tap's 50-sample traces; the stage position and the current percept.
// A GUI timer draws the newest state from the LiveFeed; data never drives a replot. A frame redraws
// the bars' own layer alone, and nothing is drawn while the tab is hidden.
#include <QLabel>
#include <QTimer>
#include <QWidget>

#include "app/gui/LiveFeed.h"

class QCPBars;
class QCPLayer;
class QCPItemText;

namespace activetouch {

class PlotPanel;

class LiveView : public QWidget {
    Q_OBJECT
public:
    LiveView(LiveFeed& feed, QWidget* parent = nullptr);

    PlotPanel* barsPanel() const { return bars_; }
    PlotPanel* tracesPanel() const { return traces_; }
    /// Frames drawn so far (for tests and the CPU benchmark); none while the view is hidden.
    std::uint64_t framesDrawn() const { return framesDrawn_; }

private:
    void tick();
    /// Takes the newest tap and frame from the feed into the plots' data; whether the bars changed.
    bool takeNewest();
    LiveFeed& feed_;
    PlotPanel* bars_;
    PlotPanel* traces_;
    QCPLayer* liveLayer_ = nullptr;
    QCPBars* barPlottable_ = nullptr;
    std::vector<QCPItemText*> readouts_;
    QLabel* pose_;
    QLabel* percept_;
    QTimer timer_;
    std::uint64_t shownTap_ = 0, shownFrame_ = 0, framesDrawn_ = 0;
    bool undrawn_ = false;  // the bars' data changed since they were last drawn
    int playback_ = 0;      // frame of the newest tap being replayed when frames are not streamed
};

}  // namespace activetouch
