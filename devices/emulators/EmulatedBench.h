#pragma once
// The emulated bench: an RCX controller on a pty carries the fingertip over the scene's object, an
// NXT brick's motor A lowers it, and a YARP publisher streams what the contact physics says the
// taxels feel at that pose and depth. The real drivers connect to it exactly as to the real rig;
// only the effects of the physics itself are present (no noise, no drift). It can run faster than
// real time (timeScale), and the drivers are told so.
#include <memory>
#include <optional>

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

    /// What the taxels feel now, counts.
    std::vector<double> fingertip();

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
};

}  // namespace activetouch::emu
