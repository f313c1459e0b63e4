#pragma once
// The emulated bench: an RCX controller on a pty carries the fingertip over the scene's object, an
// NXT brick's motor A lowers it, and a YARP publisher streams what the contact physics says the
// taxels feel at that pose and depth. The real drivers connect to it exactly as to the real rig.
// Of the scene's effects, those a frame carries are applied to every frame published when the
// scene lists them (taxel_noise and adc_quantisation), and the stage misses each target as
// stage_error says, reporting the target as a real stage does; the rest (drift, the pad's memory,
// ...) belong to the simulated rig. The reflex's latency is the bench's own: the tapper's driver
// stops the motor at the first frame over the threshold. It can run faster than real time
// (timeScale), and the drivers are told so.
#include <memory>
#include <mutex>
#include <optional>

#include "core/common/Random.h"
#include "core/fingertip/FingertipContactModel.h"
#include "core/scene/Scene.h"
#include "devices/emulators/FakeNxtBrick.h"
#include "devices/emulators/FakeRcxController.h"
#include "devices/emulators/FakeYarp.h"
#include "devices/nxt/NxtTapper.h"
#include "devices/yamaha/YamahaStage.h"
#include "devices/yarp/YarpFingertip.h"

namespace activetouch::emu {

struct BenchSettings {
    double timeScale = 10.0;
    double degreesPerMm = 20.0;
    rcx::Dialect dialect = rcx::Dialect::Rcx22x;
    FakeYarpSettings yarp;
};

class EmulatedBench {
public:
    EmulatedBench(const SceneSpec& scene, std::shared_ptr<const FingertipContactModel> model,
                  BenchSettings settings = {});
    ~EmulatedBench();
    /// Opens the pty and the loopback ports. Throws std::runtime_error.
    void start();

    FakeNxtBrick& brick() { return brick_; }
    FakeRcxController& rcx() { return rcx_; }
    FakeYarp& yarp() { return yarp_; }

    /// What the taxels read now, counts (with the scene's frame effects).
    std::vector<double> fingertip();
    /// The deepest indentation of each press its frames have shown so far, mm below the object's
    /// top, in order (a press ends when the fingertip leaves the object): where the motor really
    /// stopped, beside what the tapper's driver records.
    std::vector<double> pressDepths();
    /// The scene's effects this bench applies (to its frames and its stage).
    std::vector<std::string> effects() const;

    /// Driver settings that match this bench (ports, gearing, time scale).
    nxt::NxtTapperSettings tapperSettings() const;
    rcx::YamahaStageSettings stageSettings() const;
    yarp::YarpFingertipSettings fingertipSettings() const;
    double timeScale() const { return s_.timeScale; }

private:
    SceneSpec scene_;
    Polygon object_;
    std::shared_ptr<const FingertipContactModel> model_;
    BenchSettings s_;
    FakeNxtBrick brick_;
    FakeRcxController rcx_;
    FakeYarp yarp_;
    std::optional<FingertipContactModel::Contact> contact_;
    Vec2 contactPose_;
    std::mutex frameMutex_;
    std::vector<double> pressDepths_;
    double deepest_ = 0.0;          ///< of the press under way
    double noiseSigma_ = 0.0;       ///< taxel_noise, counts (0: not listed)
    std::optional<double> adcMax_;  ///< adc_quantisation's top of range
    RandomStream noise_;
    double stageSigma_ = 0.0;  ///< stage_error, mm per axis (0: not listed)
    RandomStream stageRandom_;
    std::optional<Vec2> target_;  ///< where the stage was last seen, and how far it missed it
    Vec2 miss_;
};

}  // namespace activetouch::emu
