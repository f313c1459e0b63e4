#include "app/gui/TaxelScope.h"

#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QTextStream>
#include <QVBoxLayout>
#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "app/figures/FigureLayout.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/WholeFile.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {
/// The channels' fixed scale: the fingertip's whole range of counts.
constexpr double kMostCounts = 255.0;
}  // namespace

TaxelScope::TaxelScope(QWidget* parent) : QWidget(parent), panel_(new PlotPanel("taxel_scope")) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    auto* controls = new QHBoxLayout;
    controls->addWidget(new QLabel(tr("Window")));
    window_ = new QDoubleSpinBox;
    window_->setObjectName("scopeWindow");
    window_->setRange(kLeastWindow_s, kMostWindow_s);
    window_->setDecimals(0);
    window_->setSuffix(tr(" s"));
    window_->setValue(10.0);
    window_->setToolTip(tr("How many seconds the scope shows (2-60; the last minute is kept)"));
    connect(window_, &QDoubleSpinBox::valueChanged, this, [this] {
        undrawn_ = true;
        redraw();
    });
    controls->addWidget(window_);
    auto* exportButton = new QPushButton(tr("Export shown as CSV..."));
    exportButton->setObjectName("scopeExport");
    exportButton->setToolTip(
        tr("Write the frames in the time range shown: time, every taxel and the total"));
    connect(exportButton, &QPushButton::clicked, this, &TaxelScope::exportWithDialog);
    controls->addWidget(exportButton);
    controls->addStretch(1);
    layout->addLayout(controls);
    layout->addWidget(panel_, 1);

    QCustomPlot& p = panel_->plot();
    p.plotLayout()->insertRow(0);
    p.plotLayout()->addElement(
        0, 0, new QCPTextElement(&p, tr("Taxel scope"), QFont("Sans", 11, QFont::Bold)));
    // Redrawn at 50 Hz, cheaply: the axis shown counts seconds before the newest frame and so
    // stays still; the traces run on a hidden axis of the time since the view began, which
    // follows it (and so does a zoom while paused), in a paint buffer of their own that is all a
    // frame redraws; their lines are not antialiased.
    p.setNotAntialiasedElements(QCP::aeAll);
    p.xAxis->setLabel(tr("time before the newest frame (s)"));
    p.xAxis2->setLabel(tr("time (s)"));
    p.xAxis2->setVisible(false);
    connect(p.xAxis, qOverload<const QCPRange&>(&QCPAxis::rangeChanged), this,
            [this](const QCPRange& r) {
                panel_->plot().xAxis2->setRange(newest_ + r.lower, newest_ + r.upper);
            });
    p.addLayer("scope", p.layer("main"), QCustomPlot::limAbove);
    traces_ = p.layer("scope");
    traces_->setMode(QCPLayer::lmBuffered);
    p.yAxis->setLabel(tr("pressure (counts)"));
    p.yAxis->setRange(0, kMostCounts);
    p.yAxis2->setVisible(true);
    p.yAxis2->setLabel(tr("total pressure (counts)"));
    p.yAxis2->setRange(0, kMostCounts);
    panel_->setEmptyHint(tr("Every taxel over the last seconds appears here as taps are taken."));
}

void TaxelScope::startChannels(int count) {
    QCustomPlot& p = panel_->plot();
    for (QCPGraph* g : channels_) p.removeGraph(g);
    if (total_) p.removeGraph(total_);
    if (threshold_) p.removeItem(threshold_);
    channels_.clear();
    for (int k = 0; k < count; ++k) {
        QCPGraph* g = p.addGraph(p.xAxis2, p.yAxis);
        g->setName(QString("taxel %1").arg(k));
        g->setPen(QPen(taxelColour(k), 1));  // one pixel wide: the fast way to draw a line
        g->setLayer(traces_);
        channels_.push_back(g);
    }
    total_ = p.addGraph(p.xAxis2, p.yAxis2);
    total_->setLayer(traces_);
    total_->setName(tr("total"));
    total_->setPen(QPen(Qt::black, 1));
    threshold_ = new QCPItemStraightLine(&p);
    threshold_->setClipAxisRect(p.axisRect());
    for (auto* end : {threshold_->point1, threshold_->point2}) end->setAxes(p.xAxis, p.yAxis2);
    threshold_->setPen(QPen(Qt::black, 1, Qt::DashLine));
    setContactThreshold(threshold_counts_);
    mostTotal_ = 0.0;
}

void TaxelScope::append(double t, const std::vector<double>& frame) {
    if (frame.empty()) return;
    if (static_cast<int>(frame.size()) != channels() || t < newest_)
        startChannels(int(frame.size()));
    for (std::size_t k = 0; k < frame.size(); ++k) {
        channels_[k]->addData(t, frame[k]);
        channels_[k]->data()->removeBefore(t - kMostWindow_s);
    }
    const double total = std::accumulate(frame.begin(), frame.end(), 0.0);
    total_->addData(t, total);
    total_->data()->removeBefore(t - kMostWindow_s);
    mostTotal_ = std::max(mostTotal_, total);
    newest_ = t;
    undrawn_ = true;
}

void TaxelScope::setWindowSeconds(double seconds) {
    window_->setValue(std::clamp(seconds, kLeastWindow_s, kMostWindow_s));
}

double TaxelScope::windowSeconds() const {
    return window_->value();
}

void TaxelScope::setContactThreshold(double counts) {
    threshold_counts_ = counts;
    if (!threshold_) return;
    threshold_->point1->setCoords(0.0, counts);
    threshold_->point2->setCoords(1.0, counts);
    threshold_->setVisible(counts > 0.0);
    undrawn_ = true;
}

bool TaxelScope::redraw() {
    if (!undrawn_ || !isVisible() || channels_.empty()) return false;
    QCustomPlot& p = panel_->plot();
    // A frame moves the traces alone; a new window, a larger total or a zoom redraws the axes.
    const QCPRange before = p.xAxis->range(), totalBefore = p.yAxis2->range();
    if (!panel_->isZoomed()) {
        p.xAxis->setRange(-windowSeconds(), 0.0);
        // The total's axis holds the threshold and the largest total so far.
        p.yAxis2->setRange(0.0, 1.1 * std::max({mostTotal_, threshold_counts_, kMostCounts}));
    }
    const QCPRange shown = p.xAxis->range();
    p.xAxis2->setRange(newest_ + shown.lower, newest_ + shown.upper);
    if (before == shown && totalBefore == p.yAxis2->range() && drawnOnce_)
        traces_->replot();
    else
        p.replot(QCustomPlot::rpImmediateRefresh);
    drawnOnce_ = true;
    undrawn_ = false;
    ++framesDrawn_;
    return true;
}

void TaxelScope::exportVisibleCsv(const QString& path) const {
    QByteArray bytes;
    QTextStream out(&bytes);
    out << "time_s";
    for (int k = 0; k < channels(); ++k) out << ",taxel_" << k;
    out << ",total\n";
    if (!channels_.empty()) {
        const QCPRange shown = panel_->plot().xAxis2->range();
        const auto& times = *channels_.front()->data();
        for (int i = 0; i < times.size(); ++i) {
            const double t = times.at(i)->key;
            if (t < shown.lower || t > shown.upper) continue;
            out << QString::number(t, 'f', 3);
            for (const QCPGraph* g : channels_) out << ',' << g->data()->at(i)->value;
            out << ',' << total_->data()->at(i)->value << '\n';
        }
    }
    out.flush();
    writeWholeOrThrow(path, bytes);
}

void TaxelScope::exportWithDialog() {
    const QString path = QFileDialog::getSaveFileName(
        this, tr("Export the scope's frames"), panel_->suggestedPath("csv"), tr("CSV (*.csv)"));
    if (path.isEmpty()) return;
    try {
        exportVisibleCsv(path);
        emit panel_->exported(tr("scope frames written to %1").arg(path));
    } catch (const std::exception& e) {
        emit panel_->failed(QString::fromStdString(e.what()));
    }
}

}  // namespace activetouch
