#include "core/control/FollowingSettings.h"

#include <cmath>

namespace activetouch {

const char* modeName(FollowingMode m) {
    return m == FollowingMode::Active ? "active" : "passive";
}

std::optional<FollowingMode> modeNamed(std::string_view name) {
    for (const FollowingMode m : {FollowingMode::Active, FollowingMode::Passive})
        if (name == modeName(m)) return m;
    return std::nullopt;
}

const char* perceptKindName(PerceptKind k) {
    return k == PerceptKind::Discrete ? "discrete" : "continuous";
}

std::optional<PerceptKind> perceptKindNamed(std::string_view name) {
    for (const PerceptKind k : {PerceptKind::Discrete, PerceptKind::Continuous})
        if (name == perceptKindName(k)) return k;
    return std::nullopt;
}

const std::vector<FollowingNumber>& followingNumbers() {
    using S = FollowingSettings;
    static const std::vector<FollowingNumber> numbers{
        {"follow_step_mm", 0.05, 50.0, &S::followStep_mm},
        {"reposition_step_mm", 0.0, 50.0, &S::repositionStep_mm},
        {"plane_step_mm", 0.0, 50.0, &S::planeStep_mm},
        {"plane_retreat_step_mm", 0.0, 50.0, &S::planeRetreatStep_mm},
        {"air_inward_step_mm", 0.0, 50.0, &S::airInwardStep_mm},
        {"air_retreat_step_mm", 0.0, 50.0, &S::airRetreatStep_mm},
        {"orientation_trust_max_error_deg", 0.0, 180.0, &S::orientationTrustMaxError_deg},
        {"belief_threshold", 0.0, 0.99999999, &S::beliefThreshold},
        {"completion_radius_mm", 0.1, 100.0, &S::completionRadius_mm},
        {"lost_outside_mm", 0.1, 1000.0, &S::lostOutside_mm},
        {"lost_inside_mm", 0.1, 1000.0, &S::lostInside_mm},
        {"tap_cap_perimeters", 0.1, 100.0, &S::tapCapPerimeters},
        {"coverage_radius_mm", 0.1, 100.0, &S::coverageRadius_mm},
        {"percept_temperature", 0.0, 1e6, &S::perceptTemperature},
        {"same_edge_tolerance_deg", 0.0, 180.0, &S::sameEdgeTolerance_deg},
    };
    return numbers;
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
    if (!(perceptTemperature >= 0.0) || !std::isfinite(perceptTemperature))
        return "percept_temperature must be 0 (the tap's samples per taxel) or positive";
    if (curvatureTaps < 0 || curvatureTaps == 1)
        return "curvature_taps must be 0 (no anticipation) or at least 2";
    return {};
}

}  // namespace activetouch
