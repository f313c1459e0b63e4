#include "app/gui/LiveView.h"

#include <QGridLayout>
#include <QSplitter>
#include <QVBoxLayout>

#include "app/gui/PlotPanel.h"
#include "qcustomplot.h"

namespace activetouch {

LiveView::LiveView(LiveFeed& feed, QWidget* parent)
    : QWidget(parent),
      feed_(feed),
      bars_(new PlotPanel("live_taxels", this)),
      traces_(new PlotPanel("last_tap_traces", this)) {
    auto* layout = new QVBoxLayout(this);
    auto* info = new QGridLayout;
    pose_ = new QLabel(tr("Stage: -"));
    percept_ = new QLabel(tr("Percept: -"));
    percept_->setWordWrap(true);
    QFont big = pose_->font();
    big.setPointSizeF(big.pointSizeF() * 1.2);
    pose_->setFont(big);
    percept_->setFont(big);
    info->addWidget(pose_, 0, 0);
    info->addWidget(percept_, 0, 1);
    info->setColumnStretch(1, 1);
    layout->addLayout(info);
    auto* split = new QSplitter(Qt::Vertical);
    split->addWidget(bars_);
    split->addWidget(traces_);
    layout->addWidget(split, 1);

    QCustomPlot& b = bars_->plot();
    b.plotLayout()->insertRow(0);
    b.plotLayout()->addElement(0, 0,
                               new QCPTextElement(&b, tr("Taxel pressures (live, 50 Hz)"),
                                                  QFont("Sans", 11, QFont::Bold)));
    // The bars and readouts change at 50 Hz and nothing else does: they get a paint buffer of their
    // own, above every other layer, and each frame redraws only that buffer.
    b.setAttribute(Qt::WA_OpaquePaintEvent);  // its white background covers every pixel
    b.addLayer("live");
    liveLayer_ = b.layer("live");
    liveLayer_->setMode(QCPLayer::lmBuffered);
    barPlottable_ = new QCPBars(b.xAxis, b.yAxis);
    barPlottable_->setLayer(liveLayer_);
    barPlottable_->setBrush(QColor(31, 119, 180));
    barPlottable_->setPen(Qt::NoPen);
    QVector<double> keys, zeros;
    QSharedPointer<QCPAxisTickerText> ticker(new QCPAxisTickerText);
    for (int k = 0; k < kFingertipTaxels; ++k) {
        keys << k;
        zeros << 0.0;
        ticker->addTick(k, QString::number(k));
        auto* t = new QCPItemText(&b);
        t->position->setCoords(k, 0);
        t->setPositionAlignment(Qt::AlignBottom | Qt::AlignHCenter);
        t->setText("0");
        t->setLayer(liveLayer_);
        readouts_.push_back(t);
    }
    barPlottable_->setData(keys, zeros);
    b.xAxis->setTicker(ticker);
    b.xAxis->grid()->setZeroLinePen(Qt::NoPen);  // taxel 0 is a taxel like the others
    b.xAxis->setLabel(tr("taxel"));
    b.yAxis->setLabel(tr("pressure (counts)"));
    b.xAxis->setRange(-0.6, kFingertipTaxels - 0.4);
    b.yAxis->setRange(0, 255);  // fixed: the fingertip's whole range

    QCustomPlot& t = traces_->plot();
    t.plotLayout()->insertRow(0);
    t.plotLayout()->addElement(
        0, 0, new QCPTextElement(&t, tr("Last tap"), QFont("Sans", 11, QFont::Bold)));
    t.legend->setVisible(true);
    t.legend->setFont(QFont("Sans", 7));
    t.axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignRight);
    for (int k = 0; k < kFingertipTaxels; ++k) {
        auto* g = t.addGraph();
        g->setName(QString("taxel %1").arg(k));
        g->setPen(QPen(QColor::fromHsv(k * 360 / kFingertipTaxels, 200, 200), 1.2));
    }
    t.xAxis->setLabel(tr("time in the tap (s)"));
    t.yAxis->setLabel(tr("pressure (counts)"));
    t.xAxis->setRange(0, kSamplesPerTap / kSampleRateHz);
    t.yAxis->setRange(0, 255);

    timer_.setInterval(20);
    connect(&timer_, &QTimer::timeout, this, &LiveView::tick);
    timer_.start();
}

void LiveView::tick() {
    if (takeNewest()) undrawn_ = true;
    // The plot always holds the newest state (an export shows it); the bars are drawn only while
    // the tab is in front, and once it comes back the next tick draws what changed meanwhile.
    if (!undrawn_ || !bars_->isVisible()) return;
    liveLayer_->replot();
    undrawn_ = false;
    ++framesDrawn_;
}

bool LiveView::takeNewest() {
    const LiveFeed::Snapshot s = feed_.snapshot();
    const bool newTap = s.tapSerial != shownTap_;
    const bool newFrame = s.frameSerial != shownFrame_;
    if (!newTap && !newFrame && playback_ >= s.tap.sampleCount() - 1) return false;
    if (newTap) {
        shownTap_ = s.tapSerial;
        playback_ = 0;
        for (int k = 0; k < s.tap.taxels && k < traces_->plot().graphCount(); ++k) {
            QVector<double> x, y;
            for (int i = 0; i < s.tap.sampleCount(); ++i) {
                x << i / kSampleRateHz;
                y << s.tap.at(i, k);
            }
            traces_->plot().graph(k)->setData(x, y, true);
        }
        traces_->requestReplot();
        pose_->setText(
            tr("Stage: x %1 mm, y %2 mm").arg(s.pose.x, 0, 'f', 2).arg(s.pose.y, 0, 'f', 2));
        percept_->setText(tr("Percept: %1").arg(s.what));
    }
    // Streamed frames show as they come; otherwise the newest tap is replayed at 50 Hz.
    std::vector<double> frame;
    if (newFrame && !s.frame.empty()) {
        shownFrame_ = s.frameSerial;
        frame = s.frame;
    }
    if (frame.empty() && s.tap.sampleCount() > 0) {
        playback_ = std::min(playback_ + (newTap ? 0 : 1), s.tap.sampleCount() - 1);
        frame.assign(s.tap.frame(playback_), s.tap.frame(playback_) + s.tap.taxels);
    }
    if (frame.empty()) return false;
    QVector<double> keys, values;
    for (std::size_t k = 0; k < frame.size(); ++k) {
        keys << double(k);
        values << frame[k];
        if (k < readouts_.size()) {
            readouts_[k]->setText(QString::number(frame[k], 'f', 0));
            readouts_[k]->position->setCoords(double(k), std::min(frame[k], 235.0));
        }
    }
    barPlottable_->setData(keys, values, true);
    return true;
}

}  // namespace activetouch
