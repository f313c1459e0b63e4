#include "app/gui/LiveView.h"

#include <QGridLayout>
#include <QPushButton>
#include <QSplitter>
#include <QVBoxLayout>

#include "app/figures/FigureLayout.h"
#include "app/gui/FingertipView.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/TaxelScope.h"
#include "qcustomplot.h"

namespace activetouch {

LiveView::LiveView(LiveFeed& feed, QWidget* parent)
    : QWidget(parent),
      feed_(feed),
      bars_(new PlotPanel("live_taxels", this)),
      traces_(new PlotPanel("last_tap_traces", this)),
      fingertip_(new FingertipView(this)),
      scope_(new TaxelScope(this)) {
    clock_.start();
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(buildReadouts());
    auto* top = new QSplitter(Qt::Horizontal);
    top->addWidget(fingertip_);
    top->addWidget(bars_);
    top->setChildrenCollapsible(false);
    top->setStretchFactor(0, 1);
    top->setStretchFactor(1, 2);
    top->setSizes({320, 640});
    // The last tap beside the scope of the last seconds.
    auto* bottom = new QSplitter(Qt::Horizontal);
    bottom->addWidget(traces_);
    bottom->addWidget(scope_);
    bottom->setChildrenCollapsible(false);
    bottom->setSizes({480, 640});
    auto* split = new QSplitter(Qt::Vertical);
    split->addWidget(top);
    split->addWidget(bottom);
    split->setChildrenCollapsible(false);
    split->setStretchFactor(0, 1);
    split->setStretchFactor(1, 1);
    split->setSizes({400, 400});
    layout->addWidget(split, 1);

    buildBars();
    buildTraces();
    timer_.setInterval(20);
    connect(&timer_, &QTimer::timeout, this, &LiveView::tick);
    timer_.start();
}

QGridLayout* LiveView::buildReadouts() {
    auto* info = new QGridLayout;
    pose_ = new QLabel(tr("Stage: -"));
    pose_->setObjectName("livePose");
    tap_ = new QLabel(tr("Tap: -"));
    tap_->setObjectName("liveTap");
    tap_->setWordWrap(true);
    percept_ = new QLabel;
    percept_->setObjectName("livePercept");
    percept_->setWordWrap(true);
    percept_->hide();  // only following taps have a percept
    QFont big = pose_->font();
    big.setPointSizeF(big.pointSizeF() * 1.2);
    pose_->setFont(big);
    percept_->setFont(big);
    pause_ = new QPushButton(tr("Pause"));
    pause_->setObjectName("livePause");
    pause_->setCheckable(true);
    pause_->setToolTip(
        tr("Hold what the live view shows (the run goes on); Resume shows the "
           "newest state again (View > Pause the live view, Ctrl+Space)"));
    connect(pause_, &QPushButton::toggled, this, &LiveView::setPaused);
    info->addWidget(pose_, 0, 0);
    info->addWidget(tap_, 0, 1);
    info->addWidget(pause_, 0, 2);
    info->addWidget(percept_, 1, 0, 1, 3);
    info->setColumnStretch(1, 1);
    return info;
}

void LiveView::buildBars() {
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
    QSharedPointer<QCPAxisTickerText> ticker(new QCPAxisTickerText);
    b.setAutoAddPlottableToLegend(false);  // the axis names the taxels
    for (int k = 0; k < kFingertipTaxels; ++k) {
        // Each taxel's bar in its own colour, as in the fingertip view and every figure.
        auto* bar = new QCPBars(b.xAxis, b.yAxis);
        bar->setName(QString("taxel %1").arg(k));
        bar->setLayer(liveLayer_);
        bar->setBrush(taxelColour(k));
        bar->setPen(QPen(taxelColour(k).darker(130)));
        bar->setWidth(0.75);
        bar->setData({double(k)}, {0.0});
        barPlottables_.push_back(bar);
        ticker->addTick(k, QString::number(k));
        auto* t = new QCPItemText(&b);
        t->position->setCoords(k, 0);
        t->setPositionAlignment(Qt::AlignBottom | Qt::AlignHCenter);
        t->setText("0");
        t->setLayer(liveLayer_);
        readouts_.push_back(t);
    }
    b.xAxis->setTicker(ticker);
    b.xAxis->grid()->setZeroLinePen(Qt::NoPen);  // taxel 0 is a taxel like the others
    b.xAxis->setLabel(tr("taxel"));
    b.yAxis->setLabel(tr("pressure (counts)"));
    b.xAxis->setRange(-0.6, kFingertipTaxels - 0.4);
    b.yAxis->setRange(0, 255);  // fixed: the fingertip's whole range
}

void LiveView::buildTraces() {
    QCustomPlot& t = traces_->plot();
    t.plotLayout()->insertRow(0);
    t.plotLayout()->addElement(
        0, 0, new QCPTextElement(&t, tr("Last tap"), QFont("Sans", 11, QFont::Bold)));
    // Twelve entries: the legend goes beside the panel, clear of the traces.
    t.legend->setVisible(true);
    t.legend->setFont(QFont("Sans", 7));
    t.axisRect()->insetLayout()->take(t.legend);
    t.plotLayout()->addElement(1, 1, t.legend);
    t.plotLayout()->setColumnStretchFactor(1, 0.001);
    t.legend->setMargins(QMargins(4, 2, 4, 2));
    for (int k = 0; k < kFingertipTaxels; ++k) {
        auto* g = t.addGraph();
        g->setName(QString("taxel %1").arg(k));
        g->setPen(QPen(taxelColour(k), 1.2));
    }
    t.xAxis->setLabel(tr("time in the tap (s)"));
    t.yAxis->setLabel(tr("pressure (counts)"));
    t.xAxis->setRange(0, kSamplesPerTap / kSampleRateHz);
    t.yAxis->setRange(0, 255);
}

void LiveView::setFingertip(const FingertipSpec& fingertip, double contactThreshold) {
    fingertip_->setFingertip(fingertip);
    fingertip_->setContactThreshold(contactThreshold);
    scope_->setContactThreshold(contactThreshold);
}

void LiveView::setPaused(bool paused) {
    if (paused == paused_) return;
    paused_ = paused;
    pause_->setChecked(paused);
    pause_->setText(paused ? tr("Resume") : tr("Pause"));
    emit pausedChanged(paused);
}

void LiveView::tick() {
    if (paused_) return;  // what is shown stays; the feed keeps only the newest state
    if (takeNewest()) undrawn_ = true;
    scope_->redraw();
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
        // A following tap says its percept; a training tap says the class it was taken on.
        tap_->setText(tr("Tap: %1").arg(s.perceived ? s.what.section(": ", 0, 0) : s.what));
        percept_->setVisible(s.perceived);
        if (s.perceived) percept_->setText(tr("Percept: %1").arg(s.what.section(": ", 1)));
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
    for (std::size_t k = 0; k < frame.size(); ++k) {
        if (k < barPlottables_.size()) barPlottables_[k]->setData({double(k)}, {frame[k]}, true);
        if (k < readouts_.size()) {
            readouts_[k]->setText(QString::number(frame[k], 'f', 0));
            readouts_[k]->position->setCoords(double(k), std::min(frame[k], 235.0));
        }
    }
    fingertip_->showFrame(frame);
    scope_->append(clock_.elapsed() / 1000.0, frame);
    return true;
}

}  // namespace activetouch
