#include "app/gui/DevicesPanel.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace activetouch {

DevicesPanel::DevicesPanel(DeviceSession* session, QWidget* parent)
    : QWidget(parent), session_(session) {
    auto* layout = new QVBoxLayout(this);
    auto call = [this](auto&&... slotAndArgs) {
        QMetaObject::invokeMethod(session_, slotAndArgs..., Qt::QueuedConnection);
    };

    connect_ = new QPushButton(tr("Connect"));
    connect_->setObjectName("connectDevices");
    layout->addWidget(connect_);
    connect(connect_, &QPushButton::clicked, this, [this] {
        if (connected_)
            QMetaObject::invokeMethod(session_, &DeviceSession::disconnectDevices,
                                      Qt::QueuedConnection);
        else
            QMetaObject::invokeMethod(
                session_, [s = session_, scene = scene_] { s->connectDevices(scene); },
                Qt::QueuedConnection);
    });

    auto* stage = new QGroupBox(tr("XY stage"));
    auto* sf = new QFormLayout(stage);
    port_ = new QComboBox;
    port_->addItem(tr("simulated stage"));
    stageState_ = new QLabel(tr("disconnected"));
    position_ = new QLabel("-");
    position_->setObjectName("stagePosition");
    limits_ = new QLabel("-");
    sf->addRow(tr("Port"), port_);
    sf->addRow(tr("State"), stageState_);
    sf->addRow(tr("Position"), position_);
    sf->addRow(tr("Soft limits"), limits_);
    step_ = new QDoubleSpinBox;
    step_->setRange(0.01, 100);
    step_->setValue(1.0);
    step_->setSuffix(" mm");
    sf->addRow(tr("Jog step"), step_);
    auto* jog = new QGridLayout;
    auto jogButton = [&](const QString& text, int row, int col, double dx, double dy) {
        auto* b = new QPushButton(text);
        b->setObjectName("jog" + text);
        jog->addWidget(b, row, col);
        connect(b, &QPushButton::clicked, this, [this, dx, dy] {
            const double s = step_->value();
            QMetaObject::invokeMethod(
                session_, [x = session_, dx, dy, s] { x->jog(dx * s, dy * s); },
                Qt::QueuedConnection);
        });
    };
    jogButton("+y", 0, 1, 0, 1);
    jogButton("-x", 1, 0, -1, 0);
    jogButton("+x", 1, 2, 1, 0);
    jogButton("-y", 2, 1, 0, -1);
    auto* home = new QPushButton(tr("Home"));
    jog->addWidget(home, 1, 1);
    connect(home, &QPushButton::clicked, this, [call] { call(&DeviceSession::home); });
    sf->addRow(jog);
    gotoX_ = new QDoubleSpinBox;
    gotoY_ = new QDoubleSpinBox;
    for (auto* s : {gotoX_, gotoY_}) {
        s->setRange(-10000, 10000);
        s->setSuffix(" mm");
    }
    gotoX_->setValue(150);
    gotoY_->setValue(121);
    auto* go = new QPushButton(tr("Go to"));
    go->setObjectName("goTo");
    auto* goRow = new QHBoxLayout;
    goRow->addWidget(gotoX_);
    goRow->addWidget(gotoY_);
    goRow->addWidget(go);
    sf->addRow(tr("Target"), goRow);
    connect(go, &QPushButton::clicked, this, [this] {
        const double x = gotoX_->value(), y = gotoY_->value();
        QMetaObject::invokeMethod(
            session_, [s = session_, x, y] { s->goTo(x, y); }, Qt::QueuedConnection);
    });
    layout->addWidget(stage);

    auto* tapper = new QGroupBox(tr("NXT tapper"));
    auto* tf = new QFormLayout(tapper);
    brick_ = new QComboBox;
    brick_->addItem(tr("simulated tapper"));
    tapperState_ = new QLabel(tr("disconnected"));
    tapperState_->setObjectName("tapperState");
    battery_ = new QLabel(tr("- (no battery on the simulated tapper)"));
    threshold_ = new QDoubleSpinBox;
    threshold_->setRange(0.01, 3000);
    threshold_->setValue(250);
    threshold_->setSuffix(tr(" counts (total)"));
    auto* testTap = new QPushButton(tr("Test tap"));
    testTap->setObjectName("testTap");
    tf->addRow(tr("Brick"), brick_);
    tf->addRow(tr("Motor"), tapperState_);
    tf->addRow(tr("Battery"), battery_);
    tf->addRow(tr("Contact threshold"), threshold_);
    tf->addRow(testTap);
    connect(testTap, &QPushButton::clicked, this, [call] { call(&DeviceSession::testTap); });
    connect(threshold_, &QDoubleSpinBox::editingFinished, this, [this] {
        const double v = threshold_->value();
        QMetaObject::invokeMethod(
            session_, [s = session_, v] { s->setContactThreshold(v); }, Qt::QueuedConnection);
    });
    layout->addWidget(tapper);

    auto* finger = new QGroupBox(tr("Fingertip"));
    auto* ff = new QFormLayout(finger);
    source_ = new QComboBox;
    source_->addItem(tr("simulated fingertip"));
    ff->addRow(tr("Source"), source_);
    ff->addRow(new QLabel(tr("Its taxels show live in the Live tab.")));
    layout->addWidget(finger);
    layout->addStretch();

    connect(session_, &DeviceSession::connectedChanged, this, [this](bool on, const QString& what) {
        connected_ = on;
        connect_->setText(on ? tr("Disconnect") : tr("Connect"));
        stageState_->setText(on ? tr("connected: %1").arg(what) : tr("disconnected"));
        if (!on) tapperState_->setText(tr("disconnected"));
        limits_->setText(on ? tr("x 0..%1, y 0..%2 mm")
                                  .arg(scene_.stage.travel_mm.x)
                                  .arg(scene_.stage.travel_mm.y)
                            : "-");
        threshold_->setValue(scene_.tap.contactThreshold);
        emit log(on ? tr("devices connected (%1)").arg(what) : tr("devices disconnected"));
    });
    connect(session_, &DeviceSession::positionChanged, this, [this](double x, double y) {
        position_->setText(tr("x %1 mm, y %2 mm").arg(x, 0, 'f', 3).arg(y, 0, 'f', 3));
    });
    connect(session_, &DeviceSession::tapperState, tapperState_, &QLabel::setText);
    connect(session_, &DeviceSession::message, this, &DevicesPanel::log);
    connect(session_, &DeviceSession::failed, this, &DevicesPanel::log);
}

}  // namespace activetouch
