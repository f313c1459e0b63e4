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

namespace activetouch {

class DevicesPanel : public QWidget {
    Q_OBJECT
public:
    DevicesPanel(DeviceSession* session, QWidget* parent = nullptr);
    /// The scene the simulated devices connect to.
    void setScene(const SceneSpec& scene) { scene_ = scene; }

signals:
    void log(const QString& text);

private:
    DeviceSession* session_;
    SceneSpec scene_;
    QLabel *position_, *limits_, *stageState_, *tapperState_, *battery_;
    QDoubleSpinBox *step_, *gotoX_, *gotoY_, *threshold_;
    QComboBox *port_, *brick_, *source_;
    QPushButton* connect_;
    bool connected_ = false;
};

}  // namespace activetouch
