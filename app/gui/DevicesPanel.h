#pragma once
// The device panels (docs/window.md): the XY stage (port, connect, home, jog, go-to, position, soft
// limits), the NXT tapper (connect, battery, motor state, test tap, contact threshold) and the
// fingertip source. Every button posts to the device thread; readouts update from its signals.
#include <QList>
#include <QWidget>
#include <vector>

#include "app/gui/DeviceSession.h"

class QVBoxLayout;
class QFormLayout;
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
    /// Keeps the pickers' settings for the next start.
    ~DevicesPanel() override;
    /// The scene the simulated devices connect to.
    void setScene(const SceneSpec& scene) { scene_ = scene; }

    DeviceSession* session() const { return session_; }
    /// What the pickers say now.
    DeviceChoice choice() const;

    /// Sets the pickers from a rig file (activetouch-cli run --rig takes the same file); the
    /// settings the panel does not show (gearing, stage speed, ...) are kept for connecting. On a
    /// bad file the pickers stay as they were and `failed` names the file, the place and the fix.
    bool openRigFile(const QString& path);
    /// Writes what the pickers say as a rig file; `failed` says why not (the emulated bench is a
    /// demo, not devices a file can name).
    bool saveRigFile(const QString& path);

signals:
    void log(const QString& text);
    void failed(const QString& message);

private:
    // The constructor's parts, in the order shown, then the session's signals.
    void addConnectionButtons(QVBoxLayout* layout);
    void addStageBox(QVBoxLayout* layout);
    void addStageMoves(QFormLayout* form);  ///< jog, home and go-to
    void addTapperBox(QVBoxLayout* layout);
    void addFingertipBox(QVBoxLayout* layout);
    void addRawLog(QVBoxLayout* layout);
    void showNameServer();
    void connectSession();
    /// A picker kept across sessions: its key in the QSettings group "devices", and the widget
    /// property holding its value.
    struct KeptSetting {
        const char* key;
        QWidget* widget;
        const char* property;
    };
    std::vector<KeptSetting> keptSettings() const;
    /// The pickers as the last session left them.
    void restoreSettings();
    void saveSettings() const;
    /// A line on the panel under Connect: what the devices last said, a failure in red.
    void showStatus(const QString& text, bool failure);
    void showConnected(bool on, const QString& what);
    /// Queues `slot` to run in the session's thread.
    void callSession(void (DeviceSession::*slot)());
    void showRig(const RigConfig& rig);
    DeviceSession* session_;
    SceneSpec scene_;
    RigConfig base_;  ///< what a rig file set that the pickers do not show
    QLabel *position_, *limits_, *stageState_, *tapperState_, *battery_;
    QDoubleSpinBox *step_, *gotoX_, *gotoY_, *threshold_;
    void refreshPorts();
    QComboBox *stageKind_, *port_, *dialect_, *parity_, *tapperKind_, *brick_, *finger_, *carrier_;
    QSpinBox *baud_, *nameServerPort_;
    QLineEdit *nameServerHost_, *yarpPort_;
    QCheckBox* compensate_;
    QPlainTextEdit* rawLog_;
    QPushButton* connect_;
    QLabel* status_;
    QLabel* nameServerShown_;       ///< the name server the fingertip will ask, and why
    QList<QWidget*> needsDevices_;  ///< enabled only while connected
    QList<QWidget*> picksDevices_;  ///< enabled only while disconnected
    bool connected_ = false;
};

}  // namespace activetouch
