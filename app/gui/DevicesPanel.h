#pragma once
// The device panels (DESIGN.md §5): the XY stage (port, connect, home, jog, go-to, position, soft
// limits), the NXT tapper (connect, battery, motor state, test tap, contact threshold) and the
// fingertip source. Every button posts to the device thread; readouts update from its signals.
#include <QWidget>

#include "app/gui/DeviceSession.h"

class QLabel;
class QDoubleSpinBox;
class QComboBox;
class QPushButton;
class QLineEdit;
class QSpinBox;
class QCheckBox;
class QPlainTextEdit;

namespace activetouch {

class DevicesPanel : public QWidget {
    Q_OBJECT
public:
    DevicesPanel(DeviceSession* session, QWidget* parent = nullptr);
    /// The scene the simulated devices connect to.
    void setScene(const SceneSpec& scene) { scene_ = scene; }

    /// What the pickers say now.
    DeviceChoice choice() const;

signals:
    void log(const QString& text);

private:
    DeviceSession* session_;
    SceneSpec scene_;
    QLabel *position_, *limits_, *stageState_, *tapperState_, *battery_;
    QDoubleSpinBox *step_, *gotoX_, *gotoY_, *threshold_;
    void refreshPorts();
    QComboBox *stageKind_, *port_, *dialect_, *parity_, *tapperKind_, *brick_, *finger_, *carrier_;
    QSpinBox *baud_, *nameServerPort_;
    QLineEdit *nameServerHost_, *yarpPort_;
    QCheckBox* compensate_;
    QPlainTextEdit* rawLog_;
    QPushButton* connect_;
    bool connected_ = false;
};

}  // namespace activetouch
