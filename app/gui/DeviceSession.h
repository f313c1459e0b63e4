#pragma once
// The devices a user drives by hand from the device panels, living in their own thread so that
// the GUI never waits on them. For now the devices are the simulated rig's; the real drivers
// (Yamaha stage, NXT tapper, YARP fingertip) take the same calls.
#include <QObject>
#include <QThread>
#include <memory>

#include "app/gui/LiveFeed.h"
#include "core/scene/Scene.h"

namespace activetouch {

class SimulatedRig;

/// Lives in the device thread; every slot is called queued from the GUI.
class DeviceSession : public QObject {
    Q_OBJECT
public:
    explicit DeviceSession(LiveFeed& live);
    ~DeviceSession() override;

public slots:
    void connectDevices(const activetouch::SceneSpec& scene);
    void disconnectDevices();
    void home();
    void jog(double dx, double dy);
    void goTo(double x, double y);
    void testTap();
    void setContactThreshold(double counts);

signals:
    void connectedChanged(bool connected, const QString& description);
    void positionChanged(double x, double y);
    void tapperState(const QString& state);
    void message(const QString& text);
    void failed(const QString& message);

private:
    bool ready();
    void move(Vec2 target);
    LiveFeed& live_;
    SceneSpec scene_;
    std::unique_ptr<SimulatedRig> rig_;
};

/// Owns the device thread and the session in it.
class DeviceThread : public QObject {
    Q_OBJECT
public:
    explicit DeviceThread(LiveFeed& live, QObject* parent = nullptr);
    ~DeviceThread() override;
    DeviceSession* session() const { return session_; }

private:
    QThread thread_;
    DeviceSession* session_;
};

}  // namespace activetouch

Q_DECLARE_METATYPE(activetouch::SceneSpec)
