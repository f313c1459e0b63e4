#include "app/gui/DeviceSession.h"

#include "devices/emulators/EmulatedBench.h"
#include "devices/simulated/SimulatedWorld.h"

namespace activetouch {

DeviceSession::DeviceSession(LiveFeed& live) : live_(live) {}
DeviceSession::~DeviceSession() {
    std::lock_guard lock(rigMutex_);
    rig_.reset();
    bench_.reset();
}

void DeviceSession::interrupt() {
    std::lock_guard lock(rigMutex_);
    if (!rig_) return;
    if (auto* t = rig_->nxtTapper()) t->abort();
    if (auto* s = rig_->yamaha()) s->stop();
}

bool DeviceSession::ready() {
    if (rig_) return true;
    emit failed(tr("The devices are not connected; press Connect first."));
    return false;
}

void DeviceSession::reassemble() {
    auto model = std::make_shared<const FingertipContactModel>(scene_.fingertip);
    RigConfig config = choice_.config;
    if (choice_.emulatedBench) {
        if (!bench_) {
            emu::BenchSettings b;
            b.timeScale = 1.0;  // a demo runs in real time
            bench_ = std::make_unique<emu::EmulatedBench>(scene_, model, b);
            bench_->start();
        }
        config.stage = RigConfig::StageKind::Yamaha;
        config.yamaha = bench_->stageSettings();
        config.tapper = RigConfig::TapperKind::Nxt;
        config.nxt = bench_->tapperSettings();
        auto* bench = bench_.get();
        config.nxtTransport = [bench] {
            return std::make_unique<emu::FakeNxtTransport>(bench->brick());
        };
        config.yarp = bench_->fingertipSettings();
        config.timeScale = bench_->timeScale();
    }
    auto rig = std::make_unique<AssembledRig>(
        scene_, model, config,
        [this](const std::string& device, const std::string& dir, const std::string& text) {
            emit raw(QString::fromStdString(device), QString::fromStdString(dir),
                     QString::fromStdString(text));
        });
    std::lock_guard lock(rigMutex_);
    rig_ = std::move(rig);
}

void DeviceSession::connectDevices(const SceneSpec& scene, const DeviceChoice& choice) {
    disconnectDevices();
    try {
        scene_ = scene;
        choice_ = choice;
        reassemble();
        QString what = QString::fromStdString(rig_->config().describe());
        if (choice.emulatedBench) what = tr("emulated bench: ") + what;
        emit connectedChanged(true, what);
        emit tapperState(tr("retracted"));
        readBattery();
        const Vec2 p = rig_->rig().stage.position();
        emit positionChanged(p.x, p.y);
    } catch (const std::exception& e) {
        {
            std::lock_guard lock(rigMutex_);
            rig_.reset();
        }
        bench_.reset();
        emit connectedChanged(false, QString());
        emit failed(tr("Could not connect the devices: %1").arg(e.what()));
    }
}

void DeviceSession::disconnectDevices() {
    const bool was = rig_ != nullptr;
    {
        std::lock_guard lock(rigMutex_);
        rig_.reset();
    }
    bench_.reset();
    if (was) emit connectedChanged(false, QString());
}

void DeviceSession::readBattery() {
    if (!rig_) return;
    if (auto* brick = rig_->brick()) {
        try {
            emit battery(tr("%1 V").arg(brick->batteryMillivolts() / 1000.0, 0, 'f', 2));
        } catch (const std::exception& e) {
            emit failed(QString::fromStdString(e.what()));
        }
    } else {
        emit battery(tr("- (no battery on the simulated tapper)"));
    }
}

void DeviceSession::move(Vec2 target) {
    if (!ready()) return;
    try {
        rig_->rig().stage.moveTo(target);
        const Vec2 p = rig_->rig().stage.position();
        emit positionChanged(p.x, p.y);
    } catch (const RigError& e) {
        emit failed(QString::fromStdString(e.what()));
    }
}

void DeviceSession::home() {
    if (!ready()) return;
    if (auto* stage = rig_->yamaha()) {
        try {
            stage->home();
            emit positionChanged(stage->position().x, stage->position().y);
        } catch (const RigError& e) {
            emit failed(QString::fromStdString(e.what()));
        }
        return;
    }
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
    try {
        const TapRecord r = rig.tapper.tap();
        TapRecord shown = r;
        shown.pose = rig.stage.position();
        double peak = 0.0;
        for (double v : r.tap.samples) peak = std::max(peak, v);
        const QString ending =
            r.ending == TapEnding::ContactReflex ? tr("reflex stop") : tr("stroke limit");
        live_.publishTap(shown, tr("test tap: %1 at %2 mm indentation, peak %3 counts")
                                    .arg(ending)
                                    .arg(r.stopDepth_mm, 0, 'f', 2)
                                    .arg(peak, 0, 'f', 0));
        emit tapperState(tr("retracted (last tap: %1)").arg(ending));
    } catch (const RigError& e) {
        emit tapperState(tr("stopped after a fault"));
        emit failed(QString::fromStdString(e.what()));
    }
}

void DeviceSession::setContactThreshold(double counts) {
    scene_.tap.contactThreshold = counts;
    if (rig_) {
        if (auto* t = rig_->nxtTapper()) {
            t->setContactThreshold(counts);
        } else {
            try {
                reassemble();
            } catch (const std::exception& e) {
                emit failed(QString::fromStdString(e.what()));
            }
        }
    }
    emit message(tr("contact threshold set to %1 counts").arg(counts));
}

DeviceThread::DeviceThread(LiveFeed& live, QObject* parent)
    : QObject(parent), session_(new DeviceSession(live)) {
    qRegisterMetaType<SceneSpec>();
    qRegisterMetaType<DeviceChoice>();
    session_->moveToThread(&thread_);
    connect(&thread_, &QThread::finished, session_, &QObject::deleteLater);
    thread_.setObjectName("devices");
    thread_.start();
}

DeviceThread::~DeviceThread() {
    session_->interrupt();  // a tap or move in progress stops now
    thread_.quit();
    thread_.wait(2000);  // bounded: device calls never block for long
}

}  // namespace activetouch
