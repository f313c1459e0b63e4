#pragma once
// A rig is a stage, a tapper and a tactile sensor, each simulated or real in any mix, and a robot
// clock that says how much robot time the experiment has used.
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

class RobotClock {
public:
    virtual ~RobotClock() = default;
    /// Robot time since the rig was assembled, seconds.
    virtual double now_s() const = 0;
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
