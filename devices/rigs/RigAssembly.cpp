#include "devices/rigs/RigAssembly.h"

#include <chrono>

#include "devices/nxt/NxtUsbTransport.h"
#include "devices/simulated/SimulatedWorld.h"

namespace activetouch {
namespace {

/// Robot time of a mixed rig: the real devices' wall time (scaled) plus what the simulated
/// devices account for.
class MixedClock final : public RobotClock {
public:
    MixedClock(double scale, const SimulatedWorld* world) : wall_(scale), world_(world) {}
    double now_s() const override { return wall_.now_s() + (world_ ? world_->now_s() : 0.0); }

private:
    WallClock wall_;
    const SimulatedWorld* world_;
};

/// A simulated tapper on a real stage: the fingertip goes where the stage says it is.
class TapperOnStage final : public Tapper {
public:
    TapperOnStage(SimulatedWorld& world, Stage& stage) : world_(world), stage_(stage) {}
    TapRecord tap() override {
        world_.placeFingertip(stage_.position());
        return world_.tap();
    }

private:
    SimulatedWorld& world_;
    Stage& stage_;
};

}  // namespace

std::string RigConfig::describe() const {
    std::string s = stage == StageKind::Simulated
                        ? "stage: simulated"
                        : "stage: Yamaha RCX on " + yamaha.serial.portName;
    if (tapper == TapperKind::Simulated) return s + "; tapper and fingertip: simulated";
    return s + "; tapper: NXT" + (nxtTransport ? " (emulated)" : " over USB") +
           "; fingertip: YARP " + yarp.port + " via " + yarp.nameServerHost + ":" +
           std::to_string(yarp.nameServerPort);
}

struct AssembledRig::Parts {
    std::unique_ptr<SimulatedWorld> world;
    std::unique_ptr<SimulatedStage> simStage;
    std::unique_ptr<Tapper> simTapper;
    std::unique_ptr<SimulatedFingertip> simTip;
    std::unique_ptr<RobotClock> clock;
};

AssembledRig::AssembledRig(const SceneSpec& scene,
                           std::shared_ptr<const FingertipContactModel> model,
                           const RigConfig& config, DeviceLog log)
    : config_(config), parts_(std::make_unique<Parts>()) {
    auto logFor = [log](const std::string& device) {
        return [log, device](const std::string& d, const std::string& t) {
            if (log) log(device, d, t);
        };
    };
    const bool anySimulated = config.stage == RigConfig::StageKind::Simulated ||
                              config.tapper == RigConfig::TapperKind::Simulated;
    if (anySimulated) parts_->world = std::make_unique<SimulatedWorld>(scene, model);
    const bool allSimulated = config.stage == RigConfig::StageKind::Simulated &&
                              config.tapper == RigConfig::TapperKind::Simulated;
    try {
        if (config.stage == RigConfig::StageKind::Yamaha) {
            yamaha_ = std::make_unique<rcx::YamahaStage>(config.yamaha, logFor("stage"));
            yamaha_->connect(config.searchOrigin);
        } else {
            parts_->simStage = std::make_unique<SimulatedStage>(*parts_->world);
        }
        Stage& stage = yamaha_ ? static_cast<Stage&>(*yamaha_) : *parts_->simStage;
        // A fully simulated rig keeps the world's own clock.
        if (!allSimulated)
            parts_->clock = std::make_unique<MixedClock>(config.timeScale, parts_->world.get());
        if (config.tapper == RigConfig::TapperKind::Nxt) {
            yarpTip_ = std::make_unique<yarp::YarpFingertip>(config.yarp, logFor("fingertip"));
            yarpTip_->connect();
            std::unique_ptr<nxt::NxtTransport> transport =
                config.nxtTransport
                    ? config.nxtTransport()
                    : std::make_unique<nxt::NxtUsbTransport>(config.usbBus, config.usbAddress);
            brick_ = std::make_unique<nxt::NxtBrick>(std::move(transport));
            brick_->setRawLog(logFor("tapper"));
            nxtTapper_ = std::make_unique<nxt::NxtTapper>(*brick_, *yarpTip_, *parts_->clock,
                                                          scene.tap, config.nxt);
            nxtTapper_->setSurface(scene.tap.retractHeight_mm - scene.object.height_mm);
            battery_ = nxtTapper_->connect();
        } else if (yamaha_) {
            parts_->simTapper = std::make_unique<TapperOnStage>(*parts_->world, stage);
            parts_->simTip = std::make_unique<SimulatedFingertip>(*parts_->world);
        } else {
            parts_->simTapper = std::make_unique<SimulatedTapper>(*parts_->world);
            parts_->simTip = std::make_unique<SimulatedFingertip>(*parts_->world);
        }
    } catch (...) {
        shutdown();
        throw;
    }
}

AssembledRig::~AssembledRig() {
    shutdown();
}

SimulatedWorld* AssembledRig::world() {
    return parts_->world.get();
}

Rig AssembledRig::rig() {
    Stage& stage = yamaha_ ? static_cast<Stage&>(*yamaha_) : *parts_->simStage;
    Tapper& tapper = nxtTapper_ ? static_cast<Tapper&>(*nxtTapper_) : *parts_->simTapper;
    TactileSensor& sensor = yarpTip_ ? static_cast<TactileSensor&>(*yarpTip_) : *parts_->simTip;
    const RobotClock& clock =
        parts_->clock ? *parts_->clock : static_cast<const RobotClock&>(*parts_->world);
    return Rig{stage, tapper, sensor, clock};
}

void AssembledRig::shutdown() noexcept {
    // A tap in progress stops at its next frame and brakes on its own; nothing it uses may go
    // before it has left. Every call it makes has its own bound, so 5 s is never reached unless a
    // device breaks its bound; then the devices are left to the process rather than freed in use.
    const bool idle = !nxtTapper_ || nxtTapper_->abortAndWait(std::chrono::seconds(5));
    if (idle && nxtTapper_ && brick_ && !brick_->unplugged()) nxtTapper_->safeStop();
    if (yamaha_) yamaha_->disconnect();
    if (yarpTip_) yarpTip_->disconnect();
    if (!idle) {
        (void)nxtTapper_.release();
        (void)brick_.release();
        (void)yarpTip_.release();
        (void)parts_.release();
    }
}

}  // namespace activetouch
