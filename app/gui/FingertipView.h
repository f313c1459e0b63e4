#pragma once
// The fingertip as the skin viewers draw it: its outline seen from the pad, each taxel a disc at
// its place, filled by its pressure on the fixed 0-255 scale and ringed in the taxel's own colour
// (the one it has in every plot); beside it the total pressure over the last seconds against the
// contact threshold the tap's reflex stops at.
#include <QWidget>
#include <deque>
#include <vector>

#include "core/fingertip/FingertipSpec.h"

class QPainter;

namespace activetouch {

class FingertipView : public QWidget {
    Q_OBJECT
public:
    explicit FingertipView(QWidget* parent = nullptr);

    void setFingertip(const FingertipSpec& fingertip);
    /// The reflex's threshold on the total pressure, counts.
    void setContactThreshold(double counts);
    /// Shows `frame` (one value per taxel, counts) and adds its total to the history.
    void showFrame(const std::vector<double>& frame);

    /// The fill colour taxel `k` is drawn with now (its pressure on the fixed scale).
    QColor fillOf(int k) const;
    /// Where taxel `k`'s disc is drawn, in widget coordinates.
    QPointF centreOf(int k) const;
    /// The radius taxel discs are drawn with, pixels.
    double discRadius() const;
    /// The pressure colour for `counts` on the fixed 0-255 scale.
    static QColor pressureColour(double counts);
    double total() const { return history_.empty() ? 0.0 : history_.back(); }
    double contactThreshold() const { return threshold_; }

    QSize sizeHint() const override { return {320, 260}; }
    QSize minimumSizeHint() const override { return {200, 160}; }

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    /// paintEvent()'s parts: the pad's outline with its taxels in their colours, the colour
    /// scale under it, and the total over the last seconds against the contact threshold.
    void paintPad(QPainter& p) const;
    void paintScale(QPainter& p) const;
    void paintHistory(QPainter& p) const;
    /// The rectangle the fingertip is drawn in and the mm -> pixel map onto it.
    QRectF outlineArea() const;
    QPointF toWidget(double axial, double lateral) const;
    FingertipSpec fingertip_;
    std::vector<double> frame_;
    std::deque<double> history_;  ///< the totals of the last frames, newest last
    double threshold_ = 0.0;
};

}  // namespace activetouch
