#pragma once
// Decision making and repositioning (paper §2.3-2.4, Figures 3-4): an explicit if-then rules
// table. Each rule names the percept it applies to and the move it commands, with every step
// length taken from FollowingSettings. Nothing here knows about corners: turning at a corner must
// come from perception and repositioning.
//
// Active mode
//   edge, position in the valid range  -> follow the perceived edge
//   edge, position on the plane side   -> follow, and reposition outward along its normal
//   edge, position on the air side     -> follow, and reposition inward along its normal
//   plane                              -> move outward along the last edge's normal and back
//                                         against the heading (at a concave corner the next
//                                         edge lies ahead: stepping back lets the tip find it)
//   air                                -> move inward along the last edge's normal and back
//                                         against the heading (moving only inward after
//                                         overshooting a convex corner would run parallel to
//                                         the next edge, just outside it, reading air)
//   edge at a position where the validation found its orientation unreliable (mean angle error
//   above the trust limit), plane side   -> as plane (the orientation is not used)
//   the same, air side                   -> as air
// Continuous percept (percept: continuous), active mode
//   edge, orientation trusted          -> follow the estimated tangent, turned by the turn the
//                                         recent edge angles predict over half a step, and move
//                                         along the normal by the perceived offset from the valid
//                                         range's centre (at most reposition_step)
//   plane, air, untrusted              -> as above, from the last edge's angle
// Sequential perception (belief threshold set): below the threshold -> tap again, moving only to
//   reposition (if enabled) toward the valid range
// Passive mode (repositioning disabled; the perceived position is never used)
//   edge                               -> follow the perceived edge
//   plane or air                       -> keep the last heading
#include <string>
#include <vector>

#include "core/classify/Percept.h"
#include "core/control/FollowingSettings.h"
#include "core/control/ShortTermMemory.h"

namespace activetouch {

enum class RuleId {
    FollowInRange,
    FollowRepositionOut,
    FollowRepositionIn,
    PlaneStepBack,
    AirStepBack,
    UntrustedPlaneSide,
    UntrustedAirSide,
    PassiveFollow,
    PassiveKeepHeading,
    Sensing,
    ContinuousFollow
};

struct Rule {
    RuleId id;
    const char* name;
    FollowingMode mode;
    const char* when;
    const char* then;
};

/// The table, in the order rules are tried.
const std::vector<Rule>& decisionRules();
const Rule& ruleFor(RuleId id);

struct Decision {
    RuleId rule;
    Vec2 follow;      ///< following component of the move, mm
    Vec2 reposition;  ///< repositioning component, mm
    Vec2 move() const { return follow + reposition; }
};

/// The valid range as offsets of the tip centre from the edge along its outward normal, mm, and
/// the wider span of offsets where the validation found the perceived orientation reliable.
struct ValidOffsets {
    double low = -1.5, high = 1.5;
    double trustedLow = -1e9, trustedHigh = 1e9;
};

/// Whether the loop may use a percept's orientation (active mode): an edge inside the trusted span.
bool orientationTrusted(const Percept& percept, const ValidOffsets& valid);

/// The largest turn the continuous rule anticipates over one step, degrees: beyond it the recent
/// angles straddle a corner rather than a curve.
inline constexpr double kMaxAnticipatedTurnDeg = 30.0;

/// Decides the next move from the percept and memory.
Decision decide(const Percept& percept, const ShortTermMemory& memory, FollowingMode mode,
                const FollowingSettings& settings, const ValidOffsets& valid);

}  // namespace activetouch
