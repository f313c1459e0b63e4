#include "app/gui/DeviceSession.h"

#include "devices/simulated/SimulatedWorld.h"

namespace activetouch {

DeviceSession::DeviceSession(LiveFeed& live) : live_(live) {}
DeviceSession::~DeviceSession() = default;

bool DeviceSession::ready() {
    if (rig_) return true;
    emit failed(tr("The devices are not connected; press Connect first."));
    return false;
}

void DeviceSession::connectDevices(const SceneSpec& scene) {
    try {
        scene_ = scene;
        rig_ = std::make_unique<SimulatedRig>(
            scene, std::make_shared<const FingertipContactModel>(scene.fingertip));
        emit connectedChanged(true, tr("simulated rig: %1 at (%2, %3) mm")
                                        .arg(QString::fromStdString(scene.object.shape))
                                        .arg(scene.object.offset.x)
                                        .arg(scene.object.offset.y));
        emit tapperState(tr("retracted"));
        const Vec2 p = rig_->rig().stage.position();
        emit positionChanged(p.x, p.y);
    } catch (const std::exception& e) {
        rig_.reset();
        emit connectedChanged(false, QString());
        emit failed(tr("Could not connect the simulated devices: %1").arg(e.what()));
    }
}

void DeviceSession::disconnectDevices() {
    rig_.reset();
    emit connectedChanged(false, QString());
}

void DeviceSession::move(Vec2 target) {
    if (!ready()) return;
    try {
        rig_->rig().stage.moveTo(target);
        emit positionChanged(target.x, target.y);
    } catch (const RigError& e) {
        emit failed(QString::fromStdString(e.what()));
    }
}

void DeviceSession::home() {
    move({0.0, 0.0});
}

void DeviceSession::jog(double dx, double dy) {
    if (!ready()) return;
    move(rig_->rig().stage.position() + Vec2{dx, dy});
}

void DeviceSession::goTo(double x, double y) {
    move({x, y});
}

void DeviceSession::testTap() {
    if (!ready()) return;
    emit tapperState(tr("tapping"));
    Rig rig = rig_->rig();
    const TapRecord r = rig.tapper.tap();
    TapRecord shown = r;
    shown.pose = rig.stage.position();
    double peak = 0.0;
    for (double v : r.tap.samples) peak = std::max(peak, v);
    live_.publishTap(shown, tr("test tap: %1 at %2 mm indentation, peak %3 counts")
                                .arg(r.ending == TapEnding::ContactReflex ? tr("reflex stop")
                                                                          : tr("stroke limit"))
                                .arg(r.stopDepth_mm, 0, 'f', 2)
                                .arg(peak, 0, 'f', 0));
    emit tapperState(
        tr("retracted (last tap: %1)")
            .arg(r.ending == TapEnding::ContactReflex ? tr("reflex stop") : tr("stroke limit")));
}

void DeviceSession::setContactThreshold(double counts) {
    scene_.tap.contactThreshold = counts;
    if (rig_) connectDevices(scene_);
    emit message(tr("contact threshold set to %1 counts").arg(counts));
}

DeviceThread::DeviceThread(LiveFeed& live, QObject* parent)
    : QObject(parent), session_(new DeviceSession(live)) {
    qRegisterMetaType<SceneSpec>();
    session_->moveToThread(&thread_);
    connect(&thread_, &QThread::finished, session_, &QObject::deleteLater);
    thread_.setObjectName("devices");
    thread_.start();
}

DeviceThread::~DeviceThread() {
    thread_.quit();
    thread_.wait(2000);  // bounded: device calls never block for long
}

}  // namespace activetouch
