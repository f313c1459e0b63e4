#include "core/control/DecisionRules.h"

#include <algorithm>
#include <stdexcept>

namespace activetouch {

const std::vector<Rule>& decisionRules() {
    static const std::vector<Rule> rules{
        {RuleId::FollowInRange, "follow", FollowingMode::Active,
         "edge, position within the valid range", "follow_step along the perceived edge"},
        {RuleId::FollowRepositionOut, "follow+out", FollowingMode::Active,
         "edge, position on the plane side of the valid range",
         "follow_step along the perceived edge + reposition_step outward along its normal"},
        {RuleId::FollowRepositionIn, "follow+in", FollowingMode::Active,
         "edge, position on the air side of the valid range",
         "follow_step along the perceived edge + reposition_step inward along its normal"},
        {RuleId::PlaneStepBack, "plane:back", FollowingMode::Active, "plane",
         "plane_step outward along the last edge's normal + plane_retreat_step against the "
         "heading"},
        {RuleId::AirStepBack, "air:back", FollowingMode::Active, "air",
         "air_inward_step inward along the last edge's normal + air_retreat_step against the "
         "heading"},
        {RuleId::UntrustedPlaneSide, "untrusted:plane", FollowingMode::Active,
         "edge whose orientation is unreliable at its position, plane side of the valid range",
         "as plane"},
        {RuleId::UntrustedAirSide, "untrusted:air", FollowingMode::Active,
         "edge whose orientation is unreliable at its position, air side of the valid range",
         "as air"},
        {RuleId::PassiveFollow, "passive:follow", FollowingMode::Passive, "edge",
         "follow_step along the perceived edge"},
        {RuleId::PassiveKeepHeading, "passive:heading", FollowingMode::Passive, "plane or air",
         "follow_step along the last heading"},
        {RuleId::Sensing, "sensing", FollowingMode::Active,
         "belief below the threshold and taps left for this decision",
         "tap again; reposition_step toward the valid range first if repositioning while sensing"},
        {RuleId::ContinuousFollow, "follow:tangent", FollowingMode::Active,
         "edge (continuous percept), orientation trusted",
         "follow_step along the estimated tangent turned by the expected turn over half a step "
         "+ the offset from the valid range's centre back along the normal (at most "
         "reposition_step)"},
    };
    return rules;
}

const Rule& ruleFor(RuleId id) {
    for (const auto& r : decisionRules())
        if (r.id == id) return r;
    throw std::logic_error("rule missing from the table");
}

Decision decide(const Percept& p, const ShortTermMemory& memory, FollowingMode mode,
                const FollowingSettings& s, const ValidOffsets& valid) {
    if (mode == FollowingMode::Passive) {
        if (p.region == Region::Edge)
            return {RuleId::PassiveFollow, s.followStep_mm * followDirection(p.orientationDeg), {}};
        return {RuleId::PassiveKeepHeading, s.followStep_mm * memory.heading, {}};
    }
    if (p.continuous && p.region == Region::Edge && orientationTrusted(p, valid)) {
        // The chord to a point one step further along a contour that turns at a steady rate
        // leaves the tangent at half the turn over the step.
        const double turn = std::clamp(0.5 * s.followStep_mm * memory.turnDegPerMm(),
                                       -kMaxAnticipatedTurnDeg, kMaxAnticipatedTurnDeg);
        const Vec2 follow = s.followStep_mm * followDirection(p.orientationDeg + turn);
        const double error = p.offset_mm - 0.5 * (valid.low + valid.high);
        const double back = std::clamp(error, -s.repositionStep_mm, s.repositionStep_mm);
        return {RuleId::ContinuousFollow, follow, -back * outwardNormal(p.orientationDeg)};
    }
    if (p.region == Region::Edge && orientationTrusted(p, valid)) {
        const Vec2 follow = s.followStep_mm * followDirection(p.orientationDeg);
        const Vec2 n = outwardNormal(p.orientationDeg);
        if (p.offset_mm < valid.low)
            return {RuleId::FollowRepositionOut, follow, s.repositionStep_mm * n};
        if (p.offset_mm > valid.high)
            return {RuleId::FollowRepositionIn, follow, -s.repositionStep_mm * n};
        return {RuleId::FollowInRange, follow, {}};
    }
    const Vec2 n = outwardNormal(memory.lastEdgeDeg);
    const Vec2 planeBack = -s.planeRetreatStep_mm * memory.heading, planeOut = s.planeStep_mm * n;
    const Vec2 airBack = -s.airRetreatStep_mm * memory.heading, airIn = -s.airInwardStep_mm * n;
    if (p.region == Region::Plane) return {RuleId::PlaneStepBack, planeBack, planeOut};
    if (p.region == Region::Air) return {RuleId::AirStepBack, airBack, airIn};
    if (p.offset_mm < valid.low) return {RuleId::UntrustedPlaneSide, planeBack, planeOut};
    return {RuleId::UntrustedAirSide, airBack, airIn};
}

bool orientationTrusted(const Percept& p, const ValidOffsets& valid) {
    return p.region == Region::Edge && p.offset_mm >= valid.trustedLow &&
           p.offset_mm <= valid.trustedHigh;
}

}  // namespace activetouch
