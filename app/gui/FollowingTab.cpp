#include "app/gui/FollowingTab.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSlider>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>

#include "app/figures/FigureExport.h"
#include "app/figures/FigureLayout.h"
#include "app/figures/FollowingFigures.h"
#include "app/gui/PlotPanel.h"
#include "core/run/ExperimentRun.h"
#include "qcustomplot.h"

namespace activetouch {

FollowingTab::FollowingTab(QWidget* parent)
    : QWidget(parent),
      active_(new PlotPanel("figure8_active_paths")),
      passive_(new PlotPanel("figure7_passive_paths")),
      replay_(new PlotPanel("trial_replay")) {
    // Two views: the paths, active beside passive, at full height; and the trials' statistics
    // beside the step-by-step replay.
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    auto* views = new QTabWidget;
    auto* paths = new QSplitter(Qt::Horizontal);
    paths->addWidget(active_);
    paths->addWidget(passive_);
    paths->setStretchFactor(0, 3);
    paths->setStretchFactor(1, 2);
    views->addTab(paths, tr("Paths: active and passive"));
    auto* lower = new QSplitter(Qt::Horizontal);
    table_ = new QTableWidget(0, 10);
    table_->setObjectName("followingTrials");
    table_->setHorizontalHeaderLabels({tr("shape"), tr("mode"), tr("trial"), tr("result"),
                                       tr("taps"), tr("robot\ntime (s)"), tr("coverage\n(%)"),
                                       tr("mean dist.\n(mm)"), tr("max dist.\n(mm)"),
                                       tr("not completed:\ngot furthest")});
    table_->verticalHeader()->setVisible(false);
    table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table_->setSelectionBehavior(QAbstractItemView::SelectRows);
    lower->addWidget(table_);
    auto* replayBox = new QWidget;
    auto* rl = new QVBoxLayout(replayBox);
    auto* controls = new QHBoxLayout;
    trial_ = new QComboBox;
    slider_ = new QSlider(Qt::Horizontal);
    play_ = new QPushButton(tr("Play"));
    play_->setObjectName("replayPlay");
    play_->setToolTip(tr("Plays the trial on from the tap shown, 20 taps a second"));
    controls->addWidget(new QLabel(tr("Replay")));
    controls->addWidget(trial_);
    controls->addWidget(play_);
    controls->addWidget(slider_, 1);
    rl->addLayout(controls);
    step_ = new QLabel(tr("Run an experiment to replay its trials."));
    step_->setWordWrap(true);
    rl->addWidget(step_);
    rl->addWidget(replay_, 1);
    lower->addWidget(replayBox);
    const QString following =
        tr("Click Run whole protocol, or Run following once the classifier is trained, to follow "
           "the contours of the experiment's trials.");
    active_->setEmptyHint(following);
    passive_->setEmptyHint(following);
    replay_->setEmptyHint(tr("Pick a trial to replay it tap by tap."));
    lower->setStretchFactor(0, 4);
    lower->setStretchFactor(1, 3);
    views->addTab(lower, tr("Trials and replay"));
    layout->addWidget(views);
    player_.setInterval(50);
    connect(&player_, &QTimer::timeout, this, [this] {
        if (slider_->value() >= slider_->maximum()) return pause();
        slider_->setValue(slider_->value() + 1);
    });
    connect(play_, &QPushButton::clicked, this, [this] { playing() ? pause() : play(); });
    connect(trial_, &QComboBox::currentIndexChanged, this, [this](int i) {
        pause();
        replay(i, 0);
    });
    connect(slider_, &QSlider::valueChanged, this,
            [this](int tap) { replay(trial_->currentIndex(), tap); });
    connect(table_, &QTableWidget::cellClicked, this,
            [this](int row, int) { trial_->setCurrentIndex(row); });
}

void FollowingTab::showRun(std::shared_ptr<const RunResult> result) {
    pause();
    result_ = std::move(result);
    const RunResult& r = *result_;
    buildPathFigure(active_->plot(), r, FollowingMode::Active,
                    tr("Active contour following (ACF)"));
    buildPathFigure(passive_->plot(), r, FollowingMode::Passive,
                    tr("Passive contour following (PCF)"));
    for (auto* p : {active_, passive_}) p->plot().replot();
    table_->setRowCount(static_cast<int>(r.trials.size()));
    const QSignalBlocker block(trial_);
    trial_->clear();
    int firstLostActive = -1;
    for (std::size_t i = 0; i < r.trials.size(); ++i) {
        const TrialRun& t = r.trials[i];
        const QStringList cells{QString::fromStdString(t.label),
                                modeName(t.result.mode),
                                QString::number(t.trial),
                                trialEndName(t.result.end),
                                QString::number(t.result.taps.size()),
                                QString::number(t.result.robotTime_s, 'f', 0),
                                QString::number(100 * t.result.coverage, 'f', 0),
                                QString::number(t.result.meanContourDistance_mm, 'f', 2),
                                QString::number(t.result.maxContourDistance_mm, 'f', 2),
                                t.result.completed()
                                    ? QString()
                                    : QString::fromStdString(describePlace(t.result.furthest))};
        // Active trials are meant to complete: one that did not is marked, and the replay opens
        // on the first of them.
        const bool lostActive = t.result.mode == FollowingMode::Active && !t.result.completed();
        if (lostActive && firstLostActive < 0) firstLostActive = static_cast<int>(i);
        for (int c = 0; c < cells.size(); ++c) {
            auto* item = new QTableWidgetItem(cells[c]);
            if (lostActive) {
                item->setBackground(QColor(255, 235, 230));
                item->setForeground(QColor(Qt::black));  // readable in a dark theme too
            }
            if (c == 3) item->setToolTip(QString::fromStdString(t.result.detail));
            table_->setItem(static_cast<int>(i), c, item);
        }
        trial_->addItem(QString("%1 %2 %3")
                            .arg(modeName(t.result.mode), QString::fromStdString(t.label))
                            .arg(t.trial));
    }
    if (firstLostActive >= 0) {
        // The whole path up to where the trial ended, and the tap it ended on.
        replay(firstLostActive,
               static_cast<int>(r.trials[std::size_t(firstLostActive)].result.taps.size()) - 1);
    } else if (!r.trials.empty()) {
        replay(0, 0);
    }
}

void FollowingTab::play() {
    if (!result_ || trial_->currentIndex() < 0) return;
    // From the last tap, play starts over.
    if (slider_->value() >= slider_->maximum()) replay(trial_->currentIndex(), 0);
    player_.start();
    play_->setText(tr("Pause"));
}

void FollowingTab::pause() {
    player_.stop();
    play_->setText(tr("Play"));
}

int FollowingTab::replayedTrial() const {
    return trial_->currentIndex();
}

int FollowingTab::replayedTap() const {
    return slider_->value();
}

void FollowingTab::replay(int index, int tap) {
    if (!result_ || index < 0 || index >= static_cast<int>(result_->trials.size())) return;
    const TrialRun& t = result_->trials[static_cast<std::size_t>(index)];
    if (t.result.taps.empty()) return;
    if (trial_->currentIndex() != index) {
        const QSignalBlocker block(trial_);
        trial_->setCurrentIndex(index);
    }
    tap = std::clamp(tap, 0, static_cast<int>(t.result.taps.size()) - 1);
    {
        const QSignalBlocker block(slider_);
        slider_->setRange(0, static_cast<int>(t.result.taps.size()) - 1);
        slider_->setValue(tap);
    }
    QCustomPlot& p = replay_->plot();
    p.clearPlottables();
    p.clearItems();
    auto curve = [&](const std::vector<Vec2>& pts, bool closed, QPen pen, int dots) {
        QCPCurve* c = addPolyline(p.xAxis, p.yAxis, pts, closed);
        c->setPen(pen);
        if (dots) c->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssDisc, pen.color(), dots));
        return c;
    };
    curve(t.outline.vertices(), true, QPen(Qt::black, 2), 0);
    std::vector<Vec2> done;
    for (int i = 0; i <= tap; ++i)
        done.push_back(t.result.taps[static_cast<std::size_t>(i)].record.pose);
    curve(done, false, QPen(QColor(31, 119, 180), 1), 4);
    // A trial that did not complete: where along the contour it got furthest, a hollow diamond.
    if (!t.result.completed()) {
        const QColor orange(255, 127, 14);
        QCPCurve* furthest = curve({t.result.furthest.point}, false, QPen(orange, 2), 0);
        furthest->setScatterStyle(
            QCPScatterStyle(QCPScatterStyle::ssDiamond, QPen(orange, 2), QBrush(Qt::NoBrush), 14));
    }
    const FollowedTap& f = t.result.taps[static_cast<std::size_t>(tap)];
    curve({f.record.pose}, false, QPen(QColor(214, 39, 40), 2), 10);
    curve({f.record.pose, f.record.pose + f.decision.move()}, false,
          QPen(QColor(214, 39, 40), 2, Qt::DashLine), 0);
    p.xAxis->setLabel(tr("x (mm)"));
    p.yAxis->setLabel(tr("y (mm)"));
    const Vec2 lo = t.outline.boundingBoxMin(), hi = t.outline.boundingBoxMax();
    setEqualAspectRanges(p.axisRect(), QCPRange(lo.x - 12, hi.x + 12),
                         QCPRange(lo.y - 12, hi.y + 12));
    p.replot();
    const Rule& rule = ruleFor(f.decision.rule);
    step_->setText(tr("Tap %1 of %2 at (%3, %4) mm: perceived %5, position %6 (posterior %7). Rule "
                      "'%8': when %9, then %10. "
                      "Progress %11 mm, %12 mm from the contour.")
                       .arg(tap + 1)
                       .arg(t.result.taps.size())
                       .arg(f.record.pose.x, 0, 'f', 1)
                       .arg(f.record.pose.y, 0, 'f', 1)
                       .arg(QString::fromStdString(f.percept.shapeClass()))
                       .arg(f.percept.position)
                       .arg(f.percept.posterior, 0, 'f', 3)
                       .arg(rule.name, rule.when, rule.then)
                       .arg(f.progress_mm, 0, 'f', 0)
                       .arg(std::abs(f.contourDistance_mm), 0, 'f', 1) +
                   (t.result.completed()
                        ? QString()
                        : tr(" The trial got furthest (diamond) %1, at progress %2 mm.")
                              .arg(QString::fromStdString(describePlace(t.result.furthest)))
                              .arg(t.result.furthestProgress_mm, 0, 'f', 0)));
}

QString FollowingTab::replayText() const {
    return step_->text();
}

}  // namespace activetouch
