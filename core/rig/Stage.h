#pragma once
// The XY stage that carries the fingertip over the object (the paper's Yamaha XY-X Cartesian
// robot, or the simulated stage). Implementations: devices/simulated, devices/yamaha.
#include "core/geometry/Vec2.h"

namespace activetouch {

class Stage {
public:
    virtual ~Stage() = default;

    /// Moves the fingertip centre to `target` (stage frame, mm) and returns once it has arrived.
    /// Throws RigError if the move is refused (outside the soft limits) or fails.
    virtual void moveTo(Vec2 target) = 0;

    /// Where the stage reports the fingertip centre to be, mm.
    virtual Vec2 position() const = 0;
};

}  // namespace activetouch
