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
    if (auto* s = rig_->yamaha()) s->interrupt();
}

bool DeviceSession::connected() const {
    std::lock_guard lock(rigMutex_);
    return rig_ != nullptr;
}

bool DeviceSession::ready() {
    std::lock_guard lock(rigMutex_);
    if (!rig_) {
        emit failed(tr("The devices are not connected; press Connect first."));
        return false;
    }
    if (*lent_) {
        emit failed(tr("A run is using the devices; cancel it or wait for it to finish."));
        return false;
    }
    busy_ = true;
    return true;
}

void DeviceSession::done() {
    std::lock_guard lock(rigMutex_);
    busy_ = false;
}

std::shared_ptr<const ConnectedRig> DeviceSession::lend(QString* why) {
    std::lock_guard lock(rigMutex_);
    QString reason;
    if (!rig_)
        reason = tr("no devices are connected");
    else if (*lent_)
        reason = tr("another run is using the devices");
    else if (busy_)
        reason =
            tr("the devices are busy with a command from the Devices panel; try again when "
               "it has finished");
    if (!reason.isEmpty()) {
        if (why) *why = reason;
        return {};
    }
    *lent_ = true;
    // The lease keeps the rig alive until the run lets go, even if the session goes first.
    struct Lease {
        std::shared_ptr<AssembledRig> rig;
        ConnectedRig connected;
    };
    QString what = QString::fromStdString(rig_->config().describe());
    if (choice_.emulatedBench) what = tr("emulated bench: ") + what;
    auto* lease = new Lease{rig_, ConnectedRig{rig_->rig(), scene_.object, what.toStdString()}};
    return std::shared_ptr<const ConnectedRig>(&lease->connected,
                                               [lease, lent = lent_](const ConnectedRig*) {
                                                   delete lease;
                                                   *lent = false;
                                               });
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
    if (*lent_) {
        emit failed(tr("A run is using the devices; cancel it before connecting others."));
        return;
    }
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
    if (*lent_) {
        emit failed(tr("A run is using the devices; cancel it before disconnecting."));
        return;
    }
    const bool was = rig_ != nullptr;
    {
        std::lock_guard lock(rigMutex_);
        rig_.reset();
    }
    bench_.reset();
    if (was) emit connectedChanged(false, QString());
}

void DeviceSession::readBattery() {
    if (!ready()) return;
    if (auto* brick = rig_->brick()) {
        try {
            emit battery(tr("%1 V").arg(brick->batteryMillivolts() / 1000.0, 0, 'f', 2));
        } catch (const std::exception& e) {
            emit failed(QString::fromStdString(e.what()));
        }
    } else {
        emit battery(tr("- (no battery on the simulated tapper)"));
    }
    done();
}

void DeviceSession::move(Vec2 target) {
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
    } else {
        move({0.0, 0.0});
    }
    done();
}

void DeviceSession::jog(double dx, double dy) {
    if (!ready()) return;
    move(rig_->rig().stage.position() + Vec2{dx, dy});
    done();
}

void DeviceSession::goTo(double x, double y) {
    if (!ready()) return;
    move({x, y});
    done();
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
        live_.publishTap(shown,
                         tr("test tap: %1 at %2 mm indentation, peak %3 counts")
                             .arg(ending)
                             .arg(r.stopDepth_mm, 0, 'f', 2)
                             .arg(peak, 0, 'f', 0),
                         false);
        emit tapperState(tr("retracted (last tap: %1)").arg(ending));
    } catch (const RigError& e) {
        emit tapperState(tr("stopped after a fault"));
        emit failed(QString::fromStdString(e.what()));
    }
    done();
}

void DeviceSession::setContactThreshold(double counts) {
    if (*lent_) {
        emit failed(tr("A run is using the devices; change the threshold when it has finished."));
        return;
    }
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
    thread_.startEventLoop();
    session_->moveToThread(thread_.thread());
    connect(thread_.thread(), &QThread::finished, session_, &QObject::deleteLater);
}

DeviceThread::~DeviceThread() {
    session_->interrupt();  // a tap or move in progress stops now
    thread_.stop();         // bounded: every device call the session makes has a timeout
}

}  // namespace activetouch
