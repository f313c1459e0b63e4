#pragma once
// The devices a user drives by hand from the device panels, living in their own thread so that
// the GUI never waits on them: any mix of the simulated devices, the Yamaha stage, the NXT tapper
// and the YARP fingertip (or the emulated bench for demos), assembled as one rig.
#include <QObject>
#include <QThread>
#include <atomic>
#include <memory>
#include <mutex>

#include "app/gui/LiveFeed.h"
#include "core/run/ExperimentRun.h"
#include "core/scene/Scene.h"
#include "devices/common/DeviceWorker.h"
#include "devices/rigs/RigAssembly.h"

namespace activetouch {

namespace emu {
class EmulatedBench;
}

/// What the panels chose: the rig configuration, or the emulated bench behind the real drivers.
struct DeviceChoice {
    RigConfig config;
    bool emulatedBench = false;  ///< real drivers against the emulators (a demo, no hardware)
};

/// Lives in the device thread; every slot is called queued from the GUI.
class DeviceSession : public QObject {
    Q_OBJECT
public:
    explicit DeviceSession(LiveFeed& live);
    ~DeviceSession() override;

    /// Thread-safe: stops a tap or move in progress at once (closing the window).
    void interrupt();

    /// Thread-safe: lends the connected rig to a run. Empty if nothing is connected, or if the
    /// devices are busy (a panel command, another run), with the reason in `why`. While lent, the
    /// panels' commands are refused; the run gives the rig back by dropping the lease.
    std::shared_ptr<const ConnectedRig> lend(QString* why);
    /// Thread-safe: whether devices are connected.
    bool connected() const;

public slots:
    void connectDevices(const activetouch::SceneSpec& scene,
                        const activetouch::DeviceChoice& choice);
    void disconnectDevices();
    void home();
    void jog(double dx, double dy);
    void goTo(double x, double y);
    void testTap();
    void setContactThreshold(double counts);
    void readBattery();

signals:
    void connectedChanged(bool connected, const QString& description);
    void positionChanged(double x, double y);
    void tapperState(const QString& state);
    void battery(const QString& text);
    void message(const QString& text);
    void failed(const QString& message);
    /// One line of a device's raw protocol traffic ("stage -> @SERVO ON").
    void raw(const QString& device, const QString& direction, const QString& text);

private:
    /// Claims the devices for one panel command; false (and says why) if not connected or lent.
    bool ready();
    /// Gives the devices back after a panel command.
    void done();
    void move(Vec2 target);
    void reassemble();
    LiveFeed& live_;
    SceneSpec scene_;
    DeviceChoice choice_;
    std::unique_ptr<emu::EmulatedBench> bench_;
    std::shared_ptr<AssembledRig> rig_;
    mutable std::mutex rigMutex_;  ///< guards rig_, busy_ and lent_ against the GUI thread
    bool busy_ = false;            ///< a panel command is running
    std::shared_ptr<std::atomic<bool>> lent_ = std::make_shared<std::atomic<bool>>(false);
};

/// Owns the device thread and the session in it.
class DeviceThread : public QObject {
    Q_OBJECT
public:
    explicit DeviceThread(LiveFeed& live, QObject* parent = nullptr);
    ~DeviceThread() override;
    DeviceSession* session() const { return session_; }

private:
    DeviceWorker thread_{"devices"};  ///< the session's event loop (docs/design.md §2)
    DeviceSession* session_;
};

}  // namespace activetouch

Q_DECLARE_METATYPE(activetouch::SceneSpec)
Q_DECLARE_METATYPE(activetouch::DeviceChoice)
