#include "app/gui/DevicesPanel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSerialPortInfo>
#include <QSettings>
#include <QSpinBox>
#include <QVBoxLayout>

#include "app/gui/ScrolledColumn.h"
#include "app/gui/WholeFile.h"
#include "devices/nxt/NxtUsbTransport.h"
#include "devices/rigs/RigFile.h"
#include "devices/yarp/YarpConf.h"
#include "devices/yarp/YarpProtocol.h"

namespace activetouch {

DevicesPanel::DevicesPanel(DeviceSession* session, QWidget* parent)
    : QWidget(parent), session_(session) {
    QVBoxLayout* layout = scrolledColumn(this);
    addConnectionButtons(layout);
    addStageBox(layout);
    addTapperBox(layout);
    addFingertipBox(layout);
    addRawLog(layout);
    refreshPorts();
    restoreSettings();
    connectSession();
    showConnected(false, {});
}

DevicesPanel::~DevicesPanel() {
    saveSettings();
}

std::vector<DevicesPanel::KeptSetting> DevicesPanel::keptSettings() const {
    return {{"stage", stageKind_, "currentIndex"},
            {"dialect", dialect_, "currentIndex"},
            {"parity", parity_, "currentIndex"},
            {"tapper", tapperKind_, "currentIndex"},
            {"finger", finger_, "currentIndex"},
            {"yarpCarrier", carrier_, "currentIndex"},  // 0 binary, 1 text
            {"serialPort", port_, "currentText"},
            {"baud", baud_, "value"},
            {"jogStep", step_, "value"},
            {"nameServerHost", nameServerHost_, "text"},
            {"nameServerPort", nameServerPort_, "value"},
            {"yarpPort", yarpPort_, "text"},
            {"compensateRaw", compensate_, "checked"}};
}

void DevicesPanel::restoreSettings() {
    QSettings s;
    s.beginGroup("devices");
    for (const KeptSetting& k : keptSettings()) {
        const QVariant value = s.value(k.key);
        if (!value.isValid()) continue;
        // A picker's index from another version of its list is left as it is.
        if (auto* box = qobject_cast<QComboBox*>(k.widget);
            box && QByteArray(k.property) == "currentIndex" &&
            (value.toInt() < 0 || value.toInt() >= box->count()))
            continue;
        k.widget->setProperty(k.property, value);
    }
}

void DevicesPanel::saveSettings() const {
    QSettings s;
    s.beginGroup("devices");
    for (const KeptSetting& k : keptSettings()) s.setValue(k.key, k.widget->property(k.property));
}

void DevicesPanel::showStatus(const QString& text, bool failure) {
    status_->setText(text);
    status_->setStyleSheet(failure ? "QLabel { color: #b00020; font-weight: bold; }"
                                   : "QLabel { color: #1b5e20; }");
    status_->setToolTip(text);
    status_->setVisible(!text.isEmpty());
}

void DevicesPanel::showConnected(bool on, const QString& what) {
    connected_ = on;
    connect_->setText(on ? tr("Disconnect") : tr("Connect"));
    stageState_->setText(on ? tr("connected: %1").arg(what) : tr("disconnected"));
    stageState_->setToolTip(stageState_->text());
    if (!on) tapperState_->setText(tr("disconnected"));
    // What needs the devices works only while they are connected; what picks them, only while
    // they are not (the connected devices are the ones the pickers show).
    for (QWidget* w : needsDevices_) w->setEnabled(on);
    for (QWidget* w : picksDevices_) w->setEnabled(!on);
}

void DevicesPanel::callSession(void (DeviceSession::*slot)()) {
    QMetaObject::invokeMethod(session_, slot, Qt::QueuedConnection);
}

void DevicesPanel::addConnectionButtons(QVBoxLayout* layout) {
    connect_ = new QPushButton(tr("Connect"));
    connect_->setObjectName("connectDevices");
    layout->addWidget(connect_);
    status_ = new QLabel;
    status_->setObjectName("deviceStatus");
    status_->setWordWrap(true);
    status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    status_->hide();
    layout->addWidget(status_);
    connect(connect_, &QPushButton::clicked, this, [this] {
        saveSettings();
        showStatus(connected_ ? tr("Disconnecting...") : tr("Connecting..."), false);
        if (connected_)
            QMetaObject::invokeMethod(session_, &DeviceSession::disconnectDevices,
                                      Qt::QueuedConnection);
        else
            QMetaObject::invokeMethod(
                session_,
                [s = session_, scene = scene_, c = choice()] { s->connectDevices(scene, c); },
                Qt::QueuedConnection);
    });

    auto* files = new QHBoxLayout;
    auto* openRig = new QPushButton(tr("Open rig file..."));
    openRig->setObjectName("openRigFile");
    openRig->setToolTip(tr("Set the devices from a rig file (activetouch-cli run --rig)"));
    auto* saveRig = new QPushButton(tr("Save rig file..."));
    saveRig->setObjectName("saveRigFile");
    saveRig->setToolTip(
        tr("Save these devices as a rig file, for headless runs: activetouch-cli run "
           "<experiment> --rig <file>"));
    files->addWidget(openRig);
    files->addWidget(saveRig);
    picksDevices_ << openRig;
    layout->addLayout(files);
    connect(openRig, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getOpenFileName(this, tr("Open rig file"), QString(),
                                                          tr("Rig files (*.json)"));
        if (!path.isEmpty()) openRigFile(path);
    });
    connect(saveRig, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getSaveFileName(this, tr("Save rig file"), "rig.json",
                                                          tr("Rig files (*.json)"));
        if (!path.isEmpty()) saveRigFile(path);
    });
}

void DevicesPanel::addStageBox(QVBoxLayout* layout) {
    auto* stage = new QGroupBox(tr("XY stage"));
    auto* sf = new QFormLayout(stage);
    stageKind_ = new QComboBox;
    stageKind_->setObjectName("stageKind");
    stageKind_->addItems({tr("simulated stage"), tr("Yamaha RCX on a serial port")});
    port_ = new QComboBox;
    port_->setObjectName("serialPort");
    port_->setEditable(true);
    port_->setToolTip(tr("The controller's serial port; type a path if it is not listed"));
    dialect_ = new QComboBox;
    dialect_->addItems({"RCX22x (OK / NG)", "RCX340 (RUN / END)"});
    baud_ = new QSpinBox;
    baud_->setRange(1200, 115200);
    baud_->setValue(9600);
    parity_ = new QComboBox;
    parity_->addItems({tr("odd"), tr("even"), tr("none")});
    auto* refresh = new QPushButton(tr("Refresh"));
    connect(refresh, &QPushButton::clicked, this, &DevicesPanel::refreshPorts);
    auto* portRow = new QHBoxLayout;
    portRow->addWidget(port_, 1);
    portRow->addWidget(refresh);
    stageState_ = new QLabel(tr("disconnected"));
    stageState_->setObjectName("stageState");
    position_ = new QLabel("-");
    position_->setObjectName("stagePosition");
    limits_ = new QLabel("-");
    // Long states wrap in the dock's width rather than widening it.
    for (QLabel* l : {stageState_, position_, limits_}) l->setWordWrap(true);
    picksDevices_ << stageKind_ << port_ << dialect_ << baud_ << parity_ << refresh;
    sf->addRow(tr("Device"), stageKind_);
    sf->addRow(tr("Port"), portRow);
    sf->addRow(tr("Dialect"), dialect_);
    sf->addRow(tr("Baud, parity"), [&] {
        auto* row = new QHBoxLayout;
        row->addWidget(baud_);
        row->addWidget(parity_);
        auto* w = new QWidget;
        w->setLayout(row);
        return w;
    }());
    sf->addRow(tr("State"), stageState_);
    sf->addRow(tr("Position"), position_);
    sf->addRow(tr("Soft limits"), limits_);
    addStageMoves(sf);
    layout->addWidget(stage);
}

void DevicesPanel::addStageMoves(QFormLayout* sf) {
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
        needsDevices_ << b;
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
    home->setObjectName("home");
    jog->addWidget(home, 1, 1);
    needsDevices_ << home;
    connect(home, &QPushButton::clicked, this, [this] { callSession(&DeviceSession::home); });
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
    needsDevices_ << go;
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
}

void DevicesPanel::addTapperBox(QVBoxLayout* layout) {
    auto* tapper = new QGroupBox(tr("NXT tapper"));
    auto* tf = new QFormLayout(tapper);
    tapperKind_ = new QComboBox;
    tapperKind_->setObjectName("tapperKind");
    tapperKind_->addItems({tr("simulated tapper and fingertip"),
                           tr("NXT over USB with the fingertip over YARP"),
                           tr("emulated bench: the real drivers, no hardware")});
    brick_ = new QComboBox;
    brick_->setObjectName("nxtBrick");
    tapperState_ = new QLabel(tr("disconnected"));
    tapperState_->setObjectName("tapperState");
    battery_ = new QLabel(tr("- (no battery on the simulated tapper)"));
    threshold_ = new QDoubleSpinBox;
    threshold_->setRange(0.01, 3000);
    threshold_->setValue(250);
    threshold_->setSuffix(tr(" counts (total)"));
    auto* testTap = new QPushButton(tr("Test tap"));
    testTap->setObjectName("testTap");
    tapperState_->setWordWrap(true);
    battery_->setWordWrap(true);
    needsDevices_ << testTap;
    picksDevices_ << tapperKind_ << brick_;
    tf->addRow(tr("Devices"), tapperKind_);
    tf->addRow(tr("Brick"), brick_);
    tf->addRow(tr("Motor"), tapperState_);
    tf->addRow(tr("Battery"), battery_);
    tf->addRow(tr("Contact threshold"), threshold_);
    tf->addRow(testTap);
    connect(testTap, &QPushButton::clicked, this, [this] { callSession(&DeviceSession::testTap); });
    connect(threshold_, &QDoubleSpinBox::editingFinished, this, [this] {
        const double v = threshold_->value();
        QMetaObject::invokeMethod(
            session_, [s = session_, v] { s->setContactThreshold(v); }, Qt::QueuedConnection);
    });
    layout->addWidget(tapper);
}

void DevicesPanel::addFingertipBox(QVBoxLayout* layout) {
    auto* finger = new QGroupBox(tr("Fingertip"));
    auto* ff = new QFormLayout(finger);
    nameServerHost_ = new QLineEdit;
    nameServerHost_->setObjectName("nameServerHost");
    nameServerHost_->setPlaceholderText(tr("from the YARP conf file"));
    nameServerPort_ = new QSpinBox;
    nameServerPort_->setObjectName("nameServerPort");
    nameServerPort_->setRange(0, 65535);
    nameServerPort_->setSpecialValueText(tr("from conf"));
    nameServerPort_->setValue(0);
    nameServerShown_ = new QLabel;
    nameServerShown_->setObjectName("nameServerShown");
    nameServerShown_->setWordWrap(true);
    // A conf file's path is one long word: let the dock's width decide, not the path.
    nameServerShown_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    nameServerShown_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    yarpPort_ = new QLineEdit("/icub/skin/right_hand_comp");
    yarpPort_->setObjectName("yarpPort");
    finger_ = new QComboBox;
    finger_->addItems({tr("index"), tr("middle"), tr("ring"), tr("little"), tr("thumb")});
    carrier_ = new QComboBox;
    carrier_->setObjectName("yarpCarrier");
    carrier_->addItems({tr("binary (Vector and Bottle ports)"), tr("text (Bottle ports only)")});
    carrier_->setToolTip(
        tr("The binary carrier is YARP's own and reads skinManager's Vector ports and Bottle "
           "ports. The text carrier reads Bottle ports only: a YARP 4 Vector port answers a text "
           "reader with raw memory and its publisher crashes."));
    compensate_ = new QCheckBox(tr("raw stream: compensate here (skinManager style)"));
    picksDevices_ << nameServerHost_ << nameServerPort_ << yarpPort_ << finger_ << carrier_
                  << compensate_;
    ff->addRow(tr("Name server"), [&] {
        auto* row = new QHBoxLayout;
        row->addWidget(nameServerHost_, 1);
        row->addWidget(nameServerPort_);
        auto* w = new QWidget;
        w->setLayout(row);
        return w;
    }());
    ff->addRow(tr("Asks"), nameServerShown_);
    connect(nameServerHost_, &QLineEdit::textChanged, this, &DevicesPanel::showNameServer);
    connect(nameServerPort_, &QSpinBox::valueChanged, this, &DevicesPanel::showNameServer);
    showNameServer();
    ff->addRow(tr("Port"), yarpPort_);
    ff->addRow(tr("Finger"), finger_);
    ff->addRow(tr("Carrier"), carrier_);
    ff->addRow(compensate_);
    auto* note = new QLabel(tr("Used with the NXT tapper; its taxels show live in the Live tab."));
    note->setWordWrap(true);
    ff->addRow(note);
    layout->addWidget(finger);
}

void DevicesPanel::showNameServer() {
    // Where the fingertip will ask, as connect() resolves it: the fields, else the conf file.
    try {
        const yarp::NameServerAddress a = yarp::resolveNameServer(
            nameServerHost_->text().trimmed().toStdString(), nameServerPort_->value());
        nameServerShown_->setText(tr("%1:%2 (%3)")
                                      .arg(QString::fromStdString(a.host))
                                      .arg(a.port)
                                      .arg(QString::fromStdString(a.source)));
    } catch (const yarp::YarpError& e) {
        nameServerShown_->setText(QString::fromStdString(e.what()));
    }
}

void DevicesPanel::addRawLog(QVBoxLayout* layout) {
    auto* rawBox = new QGroupBox(tr("Raw protocol log"));
    auto* rl = new QVBoxLayout(rawBox);
    rawLog_ = new QPlainTextEdit;
    rawLog_->setObjectName("rawLog");
    rawLog_->setReadOnly(true);
    rawLog_->setMaximumBlockCount(2000);
    rawLog_->setFont(QFont("monospace", 8));
    rl->addWidget(rawLog_);
    layout->addWidget(rawBox, 1);
}

void DevicesPanel::connectSession() {
    connect(session_, &DeviceSession::connectedChanged, this, [this](bool on, const QString& what) {
        showConnected(on, what);
        showStatus(on ? tr("Connected: %1").arg(what) : tr("Disconnected."), false);
        const DeviceChoice c = choice();
        const bool yamaha = c.config.stage == RigConfig::StageKind::Yamaha;
        limits_->setText(!on      ? "-"
                         : yamaha ? tr("x %1..%2, y %3..%4 mm (refused before sending)")
                                        .arg(c.config.yamaha.softMin.x)
                                        .arg(c.config.yamaha.softMax.x)
                                        .arg(c.config.yamaha.softMin.y)
                                        .arg(c.config.yamaha.softMax.y)
                                  : tr("x 0..%1, y 0..%2 mm")
                                        .arg(scene_.stage.travel_mm.x)
                                        .arg(scene_.stage.travel_mm.y));
        threshold_->setValue(scene_.tap.contactThreshold);
        emit log(on ? tr("devices connected (%1)").arg(what) : tr("devices disconnected"));
    });
    connect(session_, &DeviceSession::positionChanged, this, [this](double x, double y) {
        position_->setText(tr("x %1 mm, y %2 mm").arg(x, 0, 'f', 3).arg(y, 0, 'f', 3));
    });
    connect(session_, &DeviceSession::tapperState, tapperState_, &QLabel::setText);
    connect(session_, &DeviceSession::battery, battery_, &QLabel::setText);
    connect(session_, &DeviceSession::raw, this,
            [this](const QString& device, const QString& dir, const QString& text) {
                rawLog_->appendPlainText(device.leftJustified(9) + " " + dir + " " + text);
            });
    connect(session_, &DeviceSession::message, this, &DevicesPanel::log);
    // A failure shows on the panel, where the person who pressed the button is looking, and in
    // the log.
    connect(session_, &DeviceSession::failed, this, [this](const QString& m) {
        showStatus(m, true);
        emit log(tr("device error: %1").arg(m));
    });
}

void DevicesPanel::refreshPorts() {
    const QString current = port_->currentText();
    port_->clear();
    for (const QSerialPortInfo& info : QSerialPortInfo::availablePorts())
        port_->addItem(info.systemLocation());
    if (!current.isEmpty()) port_->setCurrentText(current);
    brick_->clear();
    try {
        for (const auto& b : nxt::NxtUsbTransport::list())
            brick_->addItem(QString::fromStdString(b.describe()),
                            QList<QVariant>{b.bus, b.address});
    } catch (const std::exception& e) {
        emit log(QString::fromStdString(e.what()));
    }
    if (brick_->count() == 0) brick_->addItem(tr("first NXT found on USB"), QList<QVariant>{0, 0});
}

}  // namespace activetouch
