#pragma once
// A rig is a stage, a tapper and a tactile sensor, each simulated or real in any mix, and a robot
// clock that says how much robot time the experiment has used.
#include <chrono>
#include <stdexcept>
#include <string>

#include "core/rig/Stage.h"
#include "core/rig/TactileSensor.h"
#include "core/rig/Tapper.h"

namespace activetouch {

/// A device refused or failed a command: the sentence names the device and what to do.
class RigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A rig that replays a recording has no tap for what was asked: the run has left what was
/// recorded (it moved elsewhere, or tapped on after the recording ended).
class RecordingLeft : public RigError {
public:
    using RigError::RigError;
};

class RobotClock {
public:
    virtual ~RobotClock() = default;
    /// Robot time since the rig was assembled, seconds.
    virtual double now_s() const = 0;
};

/// Robot time for real devices: wall time since the clock was made, times `scale` (an emulated
/// bench that runs faster than real time says how much faster).
class WallClock final : public RobotClock {
public:
    explicit WallClock(double scale = 1.0)
        : scale_(scale), start_(std::chrono::steady_clock::now()) {}
    double now_s() const override {
        return scale_ *
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    double scale_;
    std::chrono::steady_clock::time_point start_;
};

struct Rig {
    Stage& stage;
    Tapper& tapper;
    TactileSensor& sensor;
    const RobotClock& clock;

    /// Moves to `pose` and taps there.
    TapRecord tapAt(Vec2 pose) {
        stage.moveTo(pose);
        TapRecord r = tapper.tap();
        r.pose = pose;
        return r;
    }
};

}  // namespace activetouch
