#pragma once
// A rig from any mix of real and simulated devices (docs/design.md §1): the stage simulated or a
// Yamaha RCX on a serial port; the tapper and fingertip simulated together, or the NXT tapper
// with the fingertip over YARP (the NXT's reflex needs the real fingertip's pressure). A simulated
// tapper on a real stage taps where the stage reports itself. The experiment code sees only the
// Rig interfaces.
#include <memory>
#include <optional>
#include <string>

#include "core/fingertip/FingertipContactModel.h"
#include "core/scene/Scene.h"
#include "devices/nxt/NxtTapper.h"
#include "devices/yamaha/YamahaStage.h"
#include "devices/yarp/YarpFingertip.h"

namespace activetouch {

class SimulatedWorld;

struct RigConfig {
    enum class StageKind { Simulated, Yamaha } stage = StageKind::Simulated;
    enum class TapperKind { Simulated, Nxt } tapper = TapperKind::Simulated;
    rcx::YamahaStageSettings yamaha;
    bool searchOrigin = true;
    nxt::NxtTapperSettings nxt;
    /// Where the brick is: a USB bus/address (0/0: the first found), or an emulated brick.
    int usbBus = 0, usbAddress = 0;
    std::function<std::unique_ptr<nxt::NxtTransport>()> nxtTransport;  ///< overrides USB if set
    yarp::YarpFingertipSettings yarp;
    double timeScale = 1.0;  ///< robot seconds per wall second for real devices
    /// One line per device: "stage: Yamaha RCX on /dev/ttyUSB0", ...
    std::string describe() const;
};

/// Every device's raw traffic ("stage", "tapper" or "fingertip", the direction, the text). It is
/// called from whichever thread talks to that device (the fingertip's reader, the stage's serial
/// thread, the caller's), so it must be safe to call from several threads at once.
using DeviceLog = std::function<void(const std::string& device, const std::string& direction,
                                     const std::string& text)>;

class AssembledRig {
public:
    /// Connects every real device of `config` (stage servo and origin, brick keep-alive and motor
    /// reset, YARP name server and port). Throws RigError naming the device that failed; devices
    /// already connected are released.
    AssembledRig(const SceneSpec& scene, std::shared_ptr<const FingertipContactModel> model,
                 const RigConfig& config, DeviceLog log = {});
    ~AssembledRig();

    Rig rig();
    const RigConfig& config() const { return config_; }
    /// The simulated world, if any device is simulated.
    SimulatedWorld* world();
    nxt::NxtBrick* brick() { return brick_.get(); }
    nxt::NxtTapper* nxtTapper() { return nxtTapper_.get(); }
    rcx::YamahaStage* yamaha() { return yamaha_.get(); }
    yarp::YarpFingertip* fingertip() { return yarpTip_.get(); }
    std::optional<std::uint16_t> batteryMillivolts() const { return battery_; }
    /// Stops what moves (stage ETX, tapper brake and return) and disconnects, first waiting for a
    /// tap in progress, from any thread, to stop and leave the tapper. Bounded; never throws.
    void shutdown() noexcept;

private:
    struct Parts;
    RigConfig config_;
    std::unique_ptr<Parts> parts_;
    std::unique_ptr<rcx::YamahaStage> yamaha_;
    std::unique_ptr<yarp::YarpFingertip> yarpTip_;
    std::unique_ptr<nxt::NxtBrick> brick_;
    std::unique_ptr<nxt::NxtTapper> nxtTapper_;
    std::optional<std::uint16_t> battery_;
};

}  // namespace activetouch
