#include "app/gui/FingertipView.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

#include "app/figures/FigureLayout.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {
constexpr std::size_t kHistoryFrames = 250;  // 5 s at 50 frames a second
constexpr double kFullScale = 255.0;         // the fingertip's whole range, counts
constexpr double kTaxelRadius_mm = 1.4;
}  // namespace

FingertipView::FingertipView(QWidget* parent) : QWidget(parent) {
    setObjectName("fingertipView");
    setMinimumSize(minimumSizeHint());
    setToolTip(
        tr("The fingertip seen from its pad: each taxel filled by its pressure (0-255 "
           "counts), ringed in its own colour; right, the total pressure of the last 5 s "
           "against the contact threshold"));
}

void FingertipView::setFingertip(const FingertipSpec& fingertip) {
    fingertip_ = fingertip;
    update();
}

void FingertipView::setContactThreshold(double counts) {
    threshold_ = counts;
    update();
}

void FingertipView::showFrame(const std::vector<double>& frame) {
    frame_ = frame;
    double sum = 0.0;
    for (double v : frame) sum += v;
    history_.push_back(sum);
    while (history_.size() > kHistoryFrames) history_.pop_front();
    update();
}

QColor FingertipView::pressureColour(double counts) {
    static QCPColorGradient gradient = heatGradient();  // color() caches its lookup table
    const double v = std::isfinite(counts) ? std::clamp(counts, 0.0, kFullScale) : 0.0;
    return QColor(gradient.color(v, QCPRange(0.0, kFullScale)));
}

QColor FingertipView::fillOf(int k) const {
    return pressureColour(k >= 0 && k < int(frame_.size()) ? frame_[std::size_t(k)] : 0.0);
}

QRectF FingertipView::outlineArea() const {
    // The left 60 % for the fingertip, the rest for the history.
    return QRectF(8, 22, width() * 0.6 - 16, height() - 44);
}

QPointF FingertipView::toWidget(double axial, double lateral) const {
    // The finger points up the widget: its axis runs from the cylinder's start at the bottom to
    // the tip at the top; lateral is across.
    const QRectF area = outlineArea();
    const double r = fingertip_.radius, start = fingertip_.capStart - 2.0 * r;
    const double length = fingertip_.tipEnd - start + 1.0, across = 2.0 * r + 2.0;
    const double scale = std::min(area.width() / across, area.height() / length);
    const QPointF centre = area.center();
    const double midAxis = start + 0.5 * (fingertip_.tipEnd - start);
    return {centre.x() + lateral * scale, centre.y() - (axial - midAxis) * scale};
}

QPointF FingertipView::centreOf(int k) const {
    const TaxelPosition& t = fingertip_.taxels.at(std::size_t(k));
    return toWidget(t.x, t.z);
}

double FingertipView::discRadius() const {
    return kTaxelRadius_mm * std::abs(toWidget(0, 1).x() - toWidget(0, 0).x());
}

void FingertipView::paintPad(QPainter& p) const {
    // The outline: the cylinder's last stretch, then the cap to the tip.
    const double r = fingertip_.radius;
    QPainterPath outline;
    const double start = fingertip_.capStart - 2.0 * r;
    outline.moveTo(toWidget(start, -r));
    outline.lineTo(toWidget(fingertip_.capStart, -r));
    for (int i = 0; i <= 32; ++i) {
        const double a = M_PI * i / 32.0;  // around the cap from one side to the other
        outline.lineTo(
            toWidget(fingertip_.capStart + (fingertip_.tipEnd - fingertip_.capStart) * std::sin(a),
                     -r * std::cos(a)));
    }
    outline.lineTo(toWidget(start, r));
    p.setPen(QPen(palette().text().color(), 1.5));
    p.setBrush(palette().alternateBase());
    p.drawPath(outline);

    const double disc = discRadius();
    for (int k = 0; k < int(fingertip_.taxels.size()); ++k) {
        const QPointF c = centreOf(k);
        p.setPen(QPen(taxelColour(k), std::max(2.0, disc * 0.3)));
        p.setBrush(fillOf(k));
        p.drawEllipse(c, disc, disc);
        const double v = k < int(frame_.size()) ? frame_[std::size_t(k)] : 0.0;
        p.setPen(v > 150 ? Qt::black : Qt::white);
        p.drawText(QRectF(c.x() - disc, c.y() - disc, 2 * disc, 2 * disc), Qt::AlignCenter,
                   QString::number(k));
    }
}

void FingertipView::paintScale(QPainter& p) const {
    // The colour scale, under the fingertip.
    const QRectF area = outlineArea();
    const QRectF bar(area.left(), height() - 18, area.width() * 0.7, 8);
    for (int i = 0; i < int(bar.width()); ++i)
        p.fillRect(QRectF(bar.left() + i, bar.top(), 1, bar.height()),
                   pressureColour(kFullScale * i / bar.width()));
    p.setPen(palette().text().color());
    p.drawText(QRectF(bar.right() + 4, bar.top() - 5, area.width() * 0.3, 18),
               Qt::AlignLeft | Qt::AlignVCenter, tr("0-255"));
}

void FingertipView::paintHistory(QPainter& p) const {
    // The total over the last seconds, and the contact threshold.
    const QRectF h(width() * 0.6 + 4, 30, width() * 0.4 - 14, height() - 60);
    p.setBrush(Qt::NoBrush);
    p.setPen(QPen(palette().mid().color(), 1));
    p.drawRect(h);
    double top = std::max(threshold_ * 2.0, 1.0);
    for (double v : history_) top = std::max(top, v * 1.1);
    auto yOf = [&](double v) { return h.bottom() - h.height() * std::clamp(v / top, 0.0, 1.0); };
    if (threshold_ > 0) {
        p.setPen(QPen(QColor(214, 39, 40), 1.5, Qt::DashLine));
        p.drawLine(QPointF(h.left(), yOf(threshold_)), QPointF(h.right(), yOf(threshold_)));
    }
    if (history_.size() > 1) {
        QPainterPath line;
        for (std::size_t i = 0; i < history_.size(); ++i) {
            const QPointF pt(h.left() + h.width() * double(i) / (kHistoryFrames - 1),
                             yOf(history_[i]));
            if (i == 0)
                line.moveTo(pt);
            else
                line.lineTo(pt);
        }
        p.setPen(QPen(palette().text().color(), 1.5));
        p.drawPath(line);
    }
    p.setPen(palette().text().color());
    const bool contact = threshold_ > 0 && total() >= threshold_;
    p.drawText(QRectF(h.left(), 2, h.width(), 26),
               Qt::AlignLeft | Qt::AlignVCenter | Qt::TextWordWrap,
               tr("total %1 counts (last 5 s)").arg(total(), 0, 'f', 0));
    p.setPen(QColor(214, 39, 40));
    p.drawText(QRectF(h.left(), h.bottom() + 2, h.width(), 26),
               Qt::AlignLeft | Qt::AlignVCenter | Qt::TextWordWrap,
               threshold_ > 0 ? tr("- - contact at %1 counts%2")
                                    .arg(threshold_, 0, 'f', 0)
                                    .arg(contact ? tr(": in contact") : QString())
                              : tr("no threshold"));
}

void FingertipView::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    p.fillRect(rect(), palette().base());
    QFont title = font();
    title.setBold(true);
    p.setFont(title);
    p.setPen(palette().text().color());
    p.drawText(QRectF(8, 2, width() - 16, 18), Qt::AlignLeft | Qt::AlignVCenter,
               tr("Fingertip (pad view)"));
    p.setFont(font());
    if (fingertip_.taxels.empty()) return;

    paintPad(p);
    paintScale(p);
    paintHistory(p);
}

}  // namespace activetouch
