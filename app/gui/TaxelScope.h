#pragma once
// The taxel scope of the live tab (docs/window.md): every channel of the fingertip (12 taxels, or
// as many as a larger fingertip streams) over the last 2-60 s, scrolling as frames arrive, with
// their total on a second axis against the contact threshold that stops a stroke. The last minute
// is kept whatever the window shown, so a longer window shows the past at once. The value under
// the cursor is read out (PlotPanel); the samples in the time range shown export as CSV. Pausing
// the live view holds the scope too.
#include <QWidget>
#include <cstdint>
#include <vector>

class QCPGraph;
class QCPLayer;
class QCPItemStraightLine;
class QDoubleSpinBox;

namespace activetouch {

class PlotPanel;

class TaxelScope : public QWidget {
    Q_OBJECT
public:
    explicit TaxelScope(QWidget* parent = nullptr);

    /// The shortest and longest window, and the history kept, seconds.
    static constexpr double kLeastWindow_s = 2.0, kMostWindow_s = 60.0;

    PlotPanel* panel() const { return panel_; }
    /// Appends the frame read at `t` seconds (one value per channel); a frame with another
    /// number of channels than the last starts the scope afresh.
    void append(double t, const std::vector<double>& frame);
    /// Shows the last `seconds` (held to 2-60).
    void setWindowSeconds(double seconds);
    double windowSeconds() const;
    /// The total pressure that stops a stroke, counts, drawn on the total's axis.
    void setContactThreshold(double counts);
    /// Scrolls to the newest frame and draws; nothing while hidden. Returns whether it drew.
    bool redraw();
    /// Times the scope has been drawn (for the CPU benchmark).
    std::uint64_t framesDrawn() const { return framesDrawn_; }
    /// The channels shown (0 before the first frame).
    int channels() const { return static_cast<int>(channels_.size()); }
    /// Writes the samples inside the time range shown (of the time since the view began): a header
    /// `time_s,taxel_0,...,total`, then a row per frame. Throws std::runtime_error naming the file
    /// if it cannot be written.
    void exportVisibleCsv(const QString& path) const;

private:
    void startChannels(int count);
    void exportWithDialog();
    PlotPanel* panel_;
    QDoubleSpinBox* window_;
    std::vector<QCPGraph*> channels_;
    QCPGraph* total_ = nullptr;
    QCPLayer* traces_ = nullptr;  ///< the traces' own paint buffer
    bool drawnOnce_ = false;
    QCPItemStraightLine* threshold_ = nullptr;
    double threshold_counts_ = 0.0;
    double newest_ = 0.0;
    double mostTotal_ = 0.0;
    bool undrawn_ = false;
    std::uint64_t framesDrawn_ = 0;
};

}  // namespace activetouch
