#pragma once
// The simulated rig's world: one object on the stage, the fingertip over it, a robot clock, and
// the scene's effects. The ideal model (rigid stage, noise-free contact physics, real-valued
// pressures, instant reflex) is always there; every other effect runs only if the scene lists it.
// With a fixed seed the world is bit-for-bit reproducible.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/fingertip/FingertipContactModel.h"
#include "core/rig/Rig.h"
#include "core/run/SimulatedRigs.h"
#include "core/scene/Scene.h"
#include "devices/simulated/effects/Effect.h"

namespace activetouch {

class SimulatedWorld final : public RobotClock {
public:
    /// Builds the world and the listed effects. Throws InputError naming the scene file and the
    /// effect entry for an unknown effect or a missing / out-of-range parameter.
    SimulatedWorld(const SceneSpec& scene, std::shared_ptr<const FingertipContactModel> model);

    double now_s() const override { return clock_s_; }
    const SceneSpec& scene() const { return scene_; }
    const Polygon& object() const { return object_; }
    const FingertipContactModel& model() const { return *model_; }

    /// Names of the effects that exist in this world, in the order they act.
    std::vector<std::string> activeEffects() const;

    /// Stage: go to `target` (commanded); the fingertip really lands where stage effects put it.
    void moveStage(Vec2 target);
    Vec2 commandedPose() const { return commanded_; }
    /// Puts the fingertip where another (real) stage says it is, without taking robot time: a
    /// simulated tapper and fingertip on a real stage.
    void placeFingertip(Vec2 reported);
    Vec2 actualPose() const { return actual_; }

    /// Tapper: one tap at the current pose.
    TapRecord tap();
    /// The next tap's stroke stops `depth_mm` below the object's top (or at the stroke's limit)
    /// wherever the reflex would stop it, as a recorded stroke did: for replaying recorded
    /// strokes in simulation (the scene fit).
    void stopNextTapAt(double depth_mm) { forcedStop_mm_ = depth_mm; }

    /// The most recent frame the fingertip produced (the last sample of the last tap).
    void latestFrame(double* out) const;

    std::uint64_t tapsSimulated() const { return taps_; }

private:
    SceneSpec scene_;
    Polygon object_;
    std::shared_ptr<const FingertipContactModel> model_;
    std::vector<std::unique_ptr<Effect>> poseEffects_, mechanicsEffects_, signalEffects_;
    double clock_s_ = 0.0;
    Vec2 commanded_, actual_;
    std::vector<double> lastFrame_;
    std::vector<double> sampleDepths_, distinctDepths_, depthPressures_;  // reused tap to tap
    std::uint64_t taps_ = 0;
    std::optional<double> forcedStop_mm_;
};

/// The three devices of a simulated rig, sharing one world.
class SimulatedStage final : public Stage {
public:
    explicit SimulatedStage(SimulatedWorld& world) : world_(world) {}
    void moveTo(Vec2 target) override;
    Vec2 position() const override { return world_.commandedPose(); }

private:
    SimulatedWorld& world_;
};

class SimulatedTapper final : public Tapper {
public:
    explicit SimulatedTapper(SimulatedWorld& world) : world_(world) {}
    TapRecord tap() override { return world_.tap(); }

private:
    SimulatedWorld& world_;
};

class SimulatedFingertip final : public TactileSensor {
public:
    explicit SimulatedFingertip(const SimulatedWorld& world) : world_(world) {}
    int taxelCount() const override { return world_.model().taxelCount(); }
    void latestFrame(double* out) const override { world_.latestFrame(out); }

private:
    const SimulatedWorld& world_;
};

/// A complete simulated rig that owns its world and devices.
class SimulatedRig final : public SceneRig {
public:
    SimulatedRig(const SceneSpec& scene, std::shared_ptr<const FingertipContactModel> model)
        : world_(scene, std::move(model)), stage_(world_), tapper_(world_), sensor_(world_) {}
    Rig rig() override { return Rig{stage_, tapper_, sensor_, world_}; }
    SimulatedWorld& world() { return world_; }
    const Polygon& object() const override { return world_.object(); }
    std::vector<std::string> activeEffects() const override { return world_.activeEffects(); }
    std::uint64_t tapsSimulated() const override { return world_.tapsSimulated(); }

private:
    SimulatedWorld world_;
    SimulatedStage stage_;
    SimulatedTapper tapper_;
    SimulatedFingertip sensor_;
};

/// Checks every effect entry of `scene` (name and parameters) without building a world.
void validateEffects(const SceneSpec& scene);

/// The simulated rigs the run service builds (core/run/SimulatedRigs.h).
const SimulatedRigs& simulatedRigs();

}  // namespace activetouch
