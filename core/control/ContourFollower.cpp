#include "core/control/ContourFollower.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "core/classify/SequentialPerception.h"
#include "core/common/NumberText.h"
#include "core/control/ContactDetection.h"
#include "core/control/MotorCommand.h"

namespace activetouch {

const char* trialEndName(TrialEnd e) {
    switch (e) {
        case TrialEnd::Completed:
            return "completed";
        case TrialEnd::LostOutside:
            return "lost: too far outside the contour";
        case TrialEnd::LostInside:
            return "lost: too far inside the object";
        case TrialEnd::LostPlaneOrAir:
            return "lost: plane or air percepts in a row";
        case TrialEnd::TapCap:
            return "tap cap reached";
        case TrialEnd::DeviceError:
            return "device error";
        case TrialEnd::LeftRecording:
            return "left the recording";
        case TrialEnd::Cancelled:
            return "cancelled";
    }
    return "";
}

const char* placeKindName(PlaceKind kind) {
    switch (kind) {
        case PlaceKind::ConvexCorner:
            return "convex corner";
        case PlaceKind::ConcaveCorner:
            return "concave corner";
        case PlaceKind::AwayFromCorners:
            break;
    }
    return "away from corners";
}

CornerCriteria cornerCriteria(const ClassSet& classes) {
    // The smallest angle between two trained orientations; a single orientation has no corner
    // it could tell apart.
    double gap = 360.0;
    const auto& o = classes.orientationsDeg;
    for (std::size_t i = 0; i < o.size(); ++i)
        for (std::size_t j = i + 1; j < o.size(); ++j)
            if (const double d = angleDifferenceDeg(o[i], o[j]); d > 0) gap = std::min(gap, d);
    return {0.5 * gap, 0.5 * classes.positions * classes.positionStep_mm};
}

namespace {

bool isCorner(const Polygon& outline, std::size_t i, const CornerCriteria& criteria) {
    return std::abs(outline.turnDeg(i)) >= criteria.minTurn_deg;
}

/// `a` wrapped into [0, period).
double wrapped(double a, double period) {
    a = std::fmod(a, period);
    return a < 0 ? a + period : a;
}

std::string pointText(Vec2 p) {
    auto tenth = [](double v) { return numberText(std::round(v * 10.0) / 10.0 + 0.0); };
    std::string text = "(";
    text += tenth(p.x);
    text += ", ";
    text += tenth(p.y);
    text += ")";
    return text;
}

}  // namespace

ContourPlace contourPlace(const Polygon& outline, Vec2 point, double arc,
                          const CornerCriteria& criteria) {
    ContourPlace place;
    place.point = point;
    const double perimeter = outline.perimeter();
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < outline.size(); ++i) {
        if (!isCorner(outline, i, criteria)) continue;
        const double d = distance(point, outline.vertex(i));
        if (d > criteria.reach_mm || d >= nearest) continue;
        nearest = d;
        place.kind = outline.turnDeg(i) > 0 ? PlaceKind::ConvexCorner : PlaceKind::ConcaveCorner;
        place.corner = outline.vertex(i);
        double along = wrapped(arc - outline.arcLengthOfVertex(i), perimeter);
        if (along > perimeter / 2) along -= perimeter;
        place.pastCorner_mm = along;
    }
    return place;
}

std::string describePlace(const ContourPlace& place) {
    if (place.kind == PlaceKind::AwayFromCorners)
        return std::string("away from corners, at ") + pointText(place.point);
    const std::string corner =
        std::string("the ") + placeKindName(place.kind) + " " + pointText(place.corner);
    const double mm = std::round(std::abs(place.pastCorner_mm));
    std::string text = mm == 0.0 ? "at " : numberText(mm);
    if (mm != 0.0) text += place.pastCorner_mm > 0 ? " mm past " : " mm short of ";
    text += corner;
    return text;
}

void judgePlaces(const Polygon& outline, double startArc, const CornerCriteria& criteria,
                 TrialResult& r) {
    double furthest = 0.0;  // the start, where the first tap is taken
    for (const auto& t : r.taps) furthest = std::max(furthest, t.progress_mm);
    r.furthestProgress_mm = furthest;
    const double arc = startArc + furthest;
    r.furthest = contourPlace(outline, outline.pointAtArcLength(arc), arc, criteria);
    r.cornersRounded = {};
    for (std::size_t i = 0; i < outline.size(); ++i) {
        if (!isCorner(outline, i, criteria)) continue;
        const double ahead = wrapped(outline.arcLengthOfVertex(i) - startArc, outline.perimeter());
        if (!r.completed() && furthest <= ahead + criteria.reach_mm) continue;
        ++(outline.turnDeg(i) > 0 ? r.cornersRounded.convex : r.cornersRounded.concave);
    }
}

std::vector<Vec2> TrialResult::path() const {
    std::vector<Vec2> p;
    p.reserve(taps.size());
    for (const auto& t : taps) p.push_back(t.record.pose);
    return p;
}

Vec2 lowerEdgeStart(const Polygon& outline, const ValidOffsets& valid) {
    // The edge facing most nearly down (the paper's lower edge; on an outline turned any way,
    // whichever edge faces down most). A tip placed at a cusp or a sharp point would begin on a
    // corner, so among edges facing within 30 degrees of the best, the one on the straightest
    // stretch wins (the least turning within 8 mm along the outline either side of its middle),
    // then the one facing down most, then the lowest.
    const std::size_t n = outline.size();
    if (n < 3) throw std::invalid_argument("the object has no edge to start on");
    const Vec2 down{0.0, -1.0};
    double bestFacing = -2.0;
    for (std::size_t e = 0; e < n; ++e)
        bestFacing = std::max(bestFacing, dot(outline.outwardNormal(e), down));
    const double bestAngle = std::acos(std::clamp(bestFacing, -1.0, 1.0));
    constexpr double kStretch_mm = 8.0, kNear = 30.0 * M_PI / 180.0;
    auto turningAround = [&](std::size_t e) {
        // Vertices e+1, e+2, ... ahead and e, e-1, ... behind, within the stretch of the middle.
        const double half = 0.5 * distance(outline.vertex(e), outline.vertex(e + 1));
        double turn = 0.0, along = half;
        for (std::size_t k = 1; k <= n && along <= kStretch_mm; ++k) {
            turn += std::abs(outline.turnDeg((e + k) % n));
            along += distance(outline.vertex(e + k), outline.vertex(e + k + 1));
        }
        along = half;
        for (std::size_t k = 0; k < n && along <= kStretch_mm; ++k) {
            const std::size_t v = (e + n - k) % n;
            turn += std::abs(outline.turnDeg(v));
            along += distance(outline.vertex(v + n - 1), outline.vertex(v));
        }
        return turn;
    };
    std::optional<std::size_t> best;
    double bestTurn = 0.0, bestY = 0.0, chosenFacing = 0.0;
    for (std::size_t e = 0; e < n; ++e) {
        const double facing = dot(outline.outwardNormal(e), down);
        if (std::acos(std::clamp(facing, -1.0, 1.0)) > bestAngle + kNear) continue;
        const double turn = turningAround(e);
        const double y = 0.5 * (outline.vertex(e).y + outline.vertex(e + 1).y);
        bool better = !best;
        if (!better && turn < bestTurn - 1.0) better = true;
        if (!better && std::abs(turn - bestTurn) <= 1.0) {
            if (facing > chosenFacing + 1e-9)
                better = true;
            else if (facing > chosenFacing - 1e-9 && y < bestY)
                better = true;
        }
        if (better) {
            best = e;
            bestTurn = turn;
            bestY = y;
            chosenFacing = facing;
        }
    }
    const Vec2 mid = 0.5 * (outline.vertex(*best) + outline.vertex(*best + 1));
    return mid + 0.5 * (valid.low + valid.high) * outline.outwardNormal(*best);
}

double followingReach_mm(const FollowingSettings& s) {
    const double move =
        std::max({s.followStep_mm + s.repositionStep_mm, s.planeStep_mm + s.planeRetreatStep_mm,
                  s.airInwardStep_mm + s.airRetreatStep_mm});
    return s.lostOutside_mm + move;
}

std::string followingTravelProblem(const Polygon& outline, const FollowingSettings& s,
                                   Vec2 travel) {
    const double reach = followingReach_mm(s);
    const Vec2 lo = outline.boundingBoxMin(), hi = outline.boundingBoxMax();
    struct Side {
        double room;
        const char* name;
    };
    const Side sides[] = {{lo.x, "left side (x = 0)"},
                          {lo.y, "lower side (y = 0)"},
                          {travel.x - hi.x, "right side (x = travel)"},
                          {travel.y - hi.y, "upper side (y = travel)"}};
    for (const Side& side : sides) {
        if (side.room >= reach) continue;
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "a trial on this object can take the tip %.1f mm past its outline before "
                      "it counts as lost (lost_outside_mm plus the largest move), but the object "
                      "lies %.1f mm from the stage travel's %s; move the object at least %.1f mm "
                      "further in (offset_mm) or lower following.lost_outside_mm",
                      reach, side.room, side.name, reach - side.room);
        return buf;
    }
    return {};
}

std::string startProblem(const Polygon& outline, Vec2 start, const FollowingSettings& s) {
    const double sd = outline.signedDistance(start);  // + inside
    const bool outside = sd < 0;
    const double depth = std::abs(sd), limit = outside ? s.lostOutside_mm : s.lostInside_mm;
    if (depth <= limit) return {};
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "the start pose (%.2f, %.2f) mm is %.1f mm %s the object, beyond the %.1f mm at "
                  "which a trial counts as "
                  "lost; start on an edge",
                  start.x, start.y, depth, outside ? "outside" : "inside", limit);
    return buf;
}

namespace {

/// One trial's perception-action loop: its settings, the short-term memory, the belief over the
/// taps of one decision, and where along the contour it has got to (for judging only: the loop
/// never sees the outline).
class TrialLoop {
public:
    TrialLoop(const HistogramClassifier& classifier, const ClassSet& classes,
              const Polygon& outline, const TrialSetup& setup)
        : classifier_(classifier),
          classes_(classes),
          outline_(outline),
          setup_(setup),
          s_(setup.settings),
          sequential_(s_.beliefThreshold > 0.0),
          continuous_(s_.percept == PerceptKind::Continuous),
          belief_(classes),
          evidence_(sequential_ ? std::size_t(classes.classCount()) : 0),
          calibrated_(evidence_.size()),
          logLikelihoods_(continuous_ ? std::size_t(classes.classCount()) : 0),
          perimeter_(outline.perimeter()),
          startArc_(outline.nearestOutlinePoint(setup.start).arcLength),
          lastArc_(startArc_),
          corners_(cornerCriteria(classes)) {
        memory_.confirmationsNeeded =
            setup.mode == FollowingMode::Active ? s_.edgeConfirmationTaps : 1;
        if (continuous_) memory_.sameEdgeToleranceDeg = s_.sameEdgeTolerance_deg;
        memory_.lastEdgeDeg = setup.startEdgeDeg;
        memory_.heading = followDirection(setup.startEdgeDeg);
    }

    int tapCap() const {
        const int tapsPerDecision = sequential_ ? s_.maxTapsPerDecision : 1;
        return std::max(
            1, static_cast<int>(std::ceil(s_.tapCapPerimeters * perimeter_ / s_.followStep_mm)) *
                   tapsPerDecision);
    }
    double perimeter() const { return perimeter_; }
    double progress() const { return progress_; }
    double startArc() const { return startArc_; }

    /// Perceives `t` (its tap taken at `pose`) and decides; false while a sequential decision
    /// gathers more evidence.
    bool perceiveAndDecide(FollowedTap& t, Vec2 pose) {
        bool decisionMade = true;
        if (sequential_)
            decisionMade = perceiveSequentially(t);
        else if (continuous_) {
            classifier_.perceptScores(t.record.tap, logLikelihoods_.data());
            t.percept =
                perceiveContinuous(classes_, logLikelihoods_.data(),
                                   perceptTemperatureFor(s_.perceptTemperature, t.record.tap));
        } else {
            t.percept = perceive(classifier_, classes_, t.record.tap);
        }
        usableEdge_ = setup_.mode == FollowingMode::Passive
                          ? t.percept.region == Region::Edge
                          : orientationTrusted(t.percept, setup_.valid);
        if (continuous_ && decisionMade && usableEdge_ && s_.curvatureTaps >= 2)
            memory_.noteEdgeAt(pose, t.percept.orientationDeg, s_.curvatureTaps);
        if (decisionMade) t.decision = decide(t.percept, memory_, setup_.mode, s_, setup_.valid);
        return decisionMade;
    }

    /// Judges the trial at this tap: progress along the contour, distance from it, the true edge
    /// and, where it can be judged, the percept's angle error.
    void judge(FollowedTap& t, Vec2 pose) {
        const auto nearest = outline_.nearestOutlinePoint(pose);
        double delta = nearest.arcLength - lastArc_;
        if (delta > perimeter_ / 2) delta -= perimeter_;
        if (delta < -perimeter_ / 2) delta += perimeter_;
        progress_ += delta;
        lastArc_ = nearest.arcLength;
        t.progress_mm = progress_;
        t.contourDistance_mm = outline_.contains(pose) ? nearest.distance : -nearest.distance;
        t.trueEdgeDeg = degreesOf(outline_.outwardNormal(nearest.edge));
        const double offset = -t.contourDistance_mm;
        if (t.percept.continuous && t.percept.region == Region::Edge &&
            offset >= setup_.valid.low && offset <= setup_.valid.high &&
            contourPlace(outline_, nearest.point, nearest.arcLength, corners_).kind ==
                PlaceKind::AwayFromCorners)
            t.angleError_deg = angleDifferenceDeg(t.percept.orientationDeg, t.trueEdgeDeg);
    }

    void remember(const FollowedTap& t, bool decisionMade) {
        if (decisionMade) memory_.update(t.percept, usableEdge_);
    }

    /// How the trial ends at tap `t`, or nothing while it goes on.
    std::optional<TrialEnd> endAt(const FollowedTap& t, Vec2 pose, bool keepGoing) const {
        if (-t.contourDistance_mm > s_.lostOutside_mm) return TrialEnd::LostOutside;
        if (t.contourDistance_mm > s_.lostInside_mm) return TrialEnd::LostInside;
        if (memory_.planeOrAirRun >= s_.lostPlaneOrAirTaps) return TrialEnd::LostPlaneOrAir;
        if (progress_ >= perimeter_ && distance(pose, setup_.start) <= s_.completionRadius_mm)
            return TrialEnd::Completed;
        if (!keepGoing) return TrialEnd::Cancelled;
        return std::nullopt;
    }

    /// After a tap: a decision starts the next belief afresh; evidence still being gathered is
    /// shifted with the move.
    void afterMove(const FollowedTap& t, bool decisionMade) {
        if (!sequential_) return;
        if (decisionMade)
            belief_ = SequentialBelief(classes_);
        else
            belief_.shift(t.decision.move());
    }

private:
    bool perceiveSequentially(FollowedTap& t) {
        if (!s_.readsBeliefCalibration()) {
            belief_.update(classifier_, t.record.tap);
        } else {
            classifier_.logLikelihoods(t.record.tap, evidence_.data());
            calibratedLogBelief(evidence_.data(), classes_.classCount(), setup_.beliefScaling,
                                calibrated_.data());
            belief_.update(calibrated_.data());
        }
        // The calibrated belief decides on percepts (plane and air each one); the naive one, and
        // the continuous percept, on the single most likely class.
        const double believed =
            s_.calibratedBelief && !continuous_ ? belief_.perceptBelief() : belief_.bestPosterior();
        t.percept =
            continuous_
                ? perceiveContinuous(
                      classes_, belief_.logPosterior().data(),
                      belief_.taps() * perceptTemperatureFor(s_.perceptTemperature, t.record.tap))
                : perceptOf(belief_.best(), believed, classes_);
        if (believed >= s_.beliefThreshold || belief_.taps() >= s_.maxTapsPerDecision) return true;
        // Gather more evidence here; optionally reposition toward the valid range.
        t.decision = {RuleId::Sensing, {}, {}};
        if (s_.repositionWhileSensing && setup_.mode == FollowingMode::Active &&
            orientationTrusted(t.percept, setup_.valid))
            t.decision.reposition =
                decide(t.percept, memory_, setup_.mode, s_, setup_.valid).reposition;
        return false;
    }

    const HistogramClassifier& classifier_;
    const ClassSet& classes_;
    const Polygon& outline_;
    const TrialSetup& setup_;
    const FollowingSettings& s_;
    const bool sequential_, continuous_;
    ShortTermMemory memory_;
    SequentialBelief belief_;
    std::vector<double> evidence_, calibrated_, logLikelihoods_;
    const double perimeter_, startArc_;
    double lastArc_, progress_ = 0.0;
    const CornerCriteria corners_;
    bool usableEdge_ = false;
};

/// "completed after 210 taps, 212 of 212 mm of contour", and where a trial that did not
/// complete got furthest.
std::string trialDetail(const TrialResult& r, double progress, double perimeter) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s after %zu taps, %.0f of %.0f mm of contour",
                  trialEndName(r.end), r.taps.size(), progress, perimeter);
    std::string detail = buf;
    if (!r.completed()) detail += "; furthest " + describePlace(r.furthest);
    return detail;
}

}  // namespace

TrialResult runTrial(Rig& rig, const HistogramClassifier& classifier, const ClassSet& classes,
                     const Polygon& outline, const TrialSetup& setup,
                     const std::function<bool(const FollowedTap&)>& onTap) {
    TrialResult result;
    result.mode = setup.mode;
    result.end = TrialEnd::TapCap;
    TrialLoop loop(classifier, classes, outline, setup);
    const int tapCap = loop.tapCap();
    const double startTime = rig.clock.now_s();
    Vec2 pose = setup.start;
    try {
        rig.stage.moveTo(pose);
        for (int n = 0; n < tapCap; ++n) {
            TapRecord taken = rig.tapper.tap();  // a tap not taken (it threw) is not recorded
            // Kept in place: the tap's frames move into the trial's record, never copied.
            FollowedTap& t = result.taps.emplace_back();
            t.record = std::move(taken);
            t.record.pose = pose;
            t.contact = contactMade(t.record, setup.noiseFloor);
            const bool decisionMade = loop.perceiveAndDecide(t, pose);
            loop.judge(t, pose);
            loop.remember(t, decisionMade);
            const bool keepGoing = !onTap || onTap(t);
            if (const auto end = loop.endAt(t, pose, keepGoing)) {
                result.end = *end;
                break;
            }
            loop.afterMove(t, decisionMade);
            if (n + 1 < tapCap && t.decision.move() != Vec2{})
                pose = sendMotorCommand(rig.stage, pose, t.decision);
        }
    } catch (const RecordingLeft& e) {
        result.end = TrialEnd::LeftRecording;
        result.detail = e.what();
    } catch (const RigError& e) {
        result.end = TrialEnd::DeviceError;
        result.detail = e.what();
    }
    result.progress_mm = loop.progress();
    judgePlaces(outline, loop.startArc(), cornerCriteria(classes), result);
    if (result.detail.empty())
        result.detail = trialDetail(result, loop.progress(), loop.perimeter());
    result.robotTime_s = rig.clock.now_s() - startTime;
    measurePath(outline, result.path(), setup.settings.coverageRadius_mm, setup.contactRadius_mm,
                result);
    return result;
}

}  // namespace activetouch
