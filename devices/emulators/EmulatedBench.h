#pragma once
// The emulated bench: an RCX controller on a pty carries the fingertip over the scene's object, an
// NXT brick's motor A lowers it, and a YARP publisher streams what the contact physics says the
// taxels feel at that pose and depth. The real drivers connect to it exactly as to the real rig.
// Of the scene's effects, those a frame carries are applied to every frame published when the
// scene lists them: taxel_noise and adc_quantisation; the rest (drift, the pad's memory, stage
// error, ...) belong to the simulated rig. It can run faster than real time (timeScale), and the
// drivers are told so.
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
    /// The scene's effects this bench applies to its frames.
    std::vector<std::string> frameEffects() const;

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
    double noiseSigma_ = 0.0;       ///< taxel_noise, counts (0: not listed)
    std::optional<double> adcMax_;  ///< adc_quantisation's top of range
    RandomStream noise_;
};

}  // namespace activetouch::emu
