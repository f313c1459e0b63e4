#include "core/control/FollowingSettings.h"

#include <cmath>

namespace activetouch {

const char* modeName(FollowingMode m) {
    return m == FollowingMode::Active ? "active" : "passive";
}

std::string FollowingSettings::problem() const {
    auto positive = [](double v) { return std::isfinite(v) && v > 0; };
    if (!positive(followStep_mm)) return "follow_step_mm must be positive";
    if (!(repositionStep_mm >= 0) || !(planeStep_mm >= 0) || !(planeRetreatStep_mm >= 0) ||
        !(airInwardStep_mm >= 0) || !(airRetreatStep_mm >= 0))
        return "step lengths must not be negative";
    if (!positive(completionRadius_mm) || !positive(lostOutside_mm) || !positive(lostInside_mm) ||
        !positive(coverageRadius_mm))
        return "termination distances must be positive";
    if (lostPlaneOrAirTaps < 1) return "lost_plane_or_air_taps must be at least 1";
    if (edgeConfirmationTaps < 1) return "edge_confirmation_taps must be at least 1";
    if (!(beliefThreshold == 0.0 || (beliefThreshold > 0.0 && beliefThreshold < 1.0)))
        return "belief_threshold must be 0 (single-tap decisions) or between 0 and 1";
    if (maxTapsPerDecision < 1) return "max_taps_per_decision must be at least 1";
    if (!positive(tapCapPerimeters)) return "tap_cap_perimeters must be positive";
    return {};
}

}  // namespace activetouch
