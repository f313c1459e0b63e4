#pragma once
// Motor command (paper Figure 4): turns the decided move into a stage target and sends it.
#include "core/control/DecisionRules.h"
#include "core/rig/Stage.h"

namespace activetouch {

/// Moves the stage by the decision's move from `from`; returns the new commanded pose. Throws
/// RigError if the stage refuses (e.g. beyond its travel).
inline Vec2 sendMotorCommand(Stage& stage, Vec2 from, const Decision& decision) {
    const Vec2 target = from + decision.move();
    stage.moveTo(target);
    return target;
}

}  // namespace activetouch
