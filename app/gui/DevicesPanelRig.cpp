// The devices panel's rig: read from and written to rig files, shown in the panel, and read
// back as the devices chosen (DevicesPanel.h).
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

#include "app/gui/DevicesPanel.h"
#include "app/gui/ScrolledColumn.h"
#include "app/gui/WholeFile.h"
#include "devices/nxt/NxtUsbTransport.h"
#include "devices/rigs/RigFile.h"
#include "devices/yarp/YarpConf.h"
#include "devices/yarp/YarpProtocol.h"

namespace activetouch {

bool DevicesPanel::openRigFile(const QString& path) {
    try {
        const RigConfig rig = readRigFile(path.toStdString(), scene_);
        base_ = rig;
        showRig(rig);
        emit log(tr("devices set from %1: %2").arg(path, QString::fromStdString(rig.describe())));
        return true;
    } catch (const std::exception& e) {
        emit failed(tr("Could not open the rig file %1:\n%2").arg(path, e.what()));
        return false;
    }
}

bool DevicesPanel::saveRigFile(const QString& path) {
    const DeviceChoice c = choice();
    if (c.emulatedBench) {
        emit failed(
            tr("The emulated bench is a demo of the drivers without hardware, not devices "
               "a rig file can name; pick the simulated devices or the NXT, then save."));
        return false;
    }
    const QString why =
        writeFileWhole(path, QByteArray::fromStdString(rigFileJson(c.config).dump(2) + "\n"));
    if (!why.isEmpty()) {
        emit failed(tr("Could not write the rig file %1 (%2); free space on its disk or choose a "
                       "writable place. The file is as it was.")
                        .arg(path, why));
        return false;
    }
    emit log(tr("rig file saved: %1 (activetouch-cli run <experiment> --rig %1)").arg(path));
    return true;
}

void DevicesPanel::showRig(const RigConfig& r) {
    const bool yamaha = r.stage == RigConfig::StageKind::Yamaha;
    stageKind_->setCurrentIndex(yamaha ? 1 : 0);
    if (yamaha) {
        port_->setCurrentText(QString::fromStdString(r.yamaha.serial.portName));
        baud_->setValue(r.yamaha.serial.baud);
        parity_->setCurrentIndex(
            static_cast<int>(QByteArray("OEN").indexOf(r.yamaha.serial.parity)));
        dialect_->setCurrentIndex(r.yamaha.dialect == rcx::Dialect::Rcx340 ? 1 : 0);
    }
    const bool nxt = r.tapper == RigConfig::TapperKind::Nxt;
    tapperKind_->setCurrentIndex(nxt ? 1 : 0);
    if (!nxt) return;
    const QList<QVariant> where{r.usbBus, r.usbAddress};
    int brick = brick_->findData(where);
    if (brick < 0) {
        brick_->addItem(
            tr("bus %1, address %2 (from the rig file)").arg(r.usbBus).arg(r.usbAddress), where);
        brick = brick_->count() - 1;
    }
    brick_->setCurrentIndex(brick);
    nameServerHost_->setText(QString::fromStdString(r.yarp.nameServerHost));
    nameServerPort_->setValue(r.yarp.nameServerPort);
    yarpPort_->setText(QString::fromStdString(r.yarp.port));
    finger_->setCurrentIndex(static_cast<int>(r.yarp.finger) / 12);
    carrier_->setCurrentIndex(r.yarp.binaryCarrier ? 0 : 1);
    compensate_->setChecked(r.yarp.compensateRaw);
}

DeviceChoice DevicesPanel::choice() const {
    DeviceChoice c;
    RigConfig& r = c.config;
    r = base_;
    r.stage = stageKind_->currentIndex() == 1 ? RigConfig::StageKind::Yamaha
                                              : RigConfig::StageKind::Simulated;
    r.yamaha.serial.portName = port_->currentText().toStdString();
    r.yamaha.serial.baud = baud_->value();
    r.yamaha.serial.parity = "OEN"[parity_->currentIndex()];
    r.yamaha.dialect = dialect_->currentIndex() == 1 ? rcx::Dialect::Rcx340 : rcx::Dialect::Rcx22x;
    r.yamaha.softMax = scene_.stage.travel_mm;
    r.tapper = tapperKind_->currentIndex() == 1 ? RigConfig::TapperKind::Nxt
                                                : RigConfig::TapperKind::Simulated;
    c.emulatedBench = tapperKind_->currentIndex() == 2;
    const QList<QVariant> where = brick_->currentData().toList();
    if (where.size() == 2) {
        r.usbBus = where[0].toInt();
        r.usbAddress = where[1].toInt();
    }
    r.yarp.nameServerHost = nameServerHost_->text().trimmed().toStdString();
    r.yarp.nameServerPort = nameServerPort_->value();
    r.yarp.port = yarpPort_->text().toStdString();
    r.yarp.finger = static_cast<yarp::Finger>(12 * finger_->currentIndex());
    r.yarp.binaryCarrier = carrier_->currentIndex() == 0;
    r.yarp.compensateRaw = compensate_->isChecked();
    return c;
}

}  // namespace activetouch
