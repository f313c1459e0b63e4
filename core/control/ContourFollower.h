#pragma once
// The contour follower (paper §2.3-3.3, Figures 4, 7, 8): the perception-action loop run as a
// trial on any rig. Each tap: contact detection (in the tapper), classification, decision making
// with short-term memory, repositioning, motor command. Active and passive are the same loop
// with repositioning on or off.
//
// The true outline is used only to judge the trial (termination and metrics), never by the loop.
#include <functional>
#include <string>
#include <vector>

#include "core/classify/BeliefCalibration.h"
#include "core/classify/HistogramClassifier.h"
#include "core/control/DecisionRules.h"
#include "core/geometry/Polygon.h"
#include "core/rig/Rig.h"

namespace activetouch {

struct FollowedTap {
    TapRecord record;
    Percept percept;
    Decision decision;
    bool contact = false;
    double progress_mm = 0.0;  ///< unwrapped progress along the contour so far
    double contourDistance_mm =
        0.0;  ///< signed distance of the pose to the true outline (+ inside)
    /// For judging a continuous percept: the outward normal of the outline nearest the pose,
    /// degrees, and the percept's angle error against it where the percept is an edge, the tip is
    /// inside the valid range and away from corners (-1 elsewhere).
    double trueEdgeDeg = 0.0;
    double angleError_deg = -1.0;
};

enum class TrialEnd {
    Completed,
    LostOutside,
    LostInside,
    LostPlaneOrAir,
    TapCap,
    DeviceError,
    LeftRecording,  ///< replayed on a recording, the trial asked for a tap it does not hold
    Cancelled
};
const char* trialEndName(TrialEnd e);

/// Where on the contour a point lies, for judging trials (never used by the loop): near a
/// corner, or away from corners.
enum class PlaceKind { AwayFromCorners, ConvexCorner, ConcaveCorner };
const char* placeKindName(PlaceKind kind);  ///< "away from corners", "convex corner", ...

/// What counts as a corner, from the perceptual classes: a vertex where the outline turns by at
/// least half the smallest angle between trained orientations (45 degrees for the paper's four;
/// the bends of a 64-gon circle are no corners), and "near" it means within half the classes'
/// window (9 mm for 18 positions at 1 mm), where the fingertip's taps reach it.
struct CornerCriteria {
    double minTurn_deg = 45.0;
    double reach_mm = 9.0;
};
CornerCriteria cornerCriteria(const ClassSet& classes);

struct ContourPlace {
    PlaceKind kind = PlaceKind::AwayFromCorners;
    Vec2 point;                  ///< the point on the outline
    Vec2 corner;                 ///< the nearest corner's vertex (corner kinds)
    double pastCorner_mm = 0.0;  ///< along the contour from the corner: + past it, - short of it
};

/// The place of outline point `point` (at arc length `arc`): the nearest corner within the
/// reach, else away from corners.
ContourPlace contourPlace(const Polygon& outline, Vec2 point, double arc,
                          const CornerCriteria& criteria);

/// "3 mm past the convex corner (174, 121)", "away from corners, at (150, 121)".
std::string describePlace(const ContourPlace& place);

struct CornerCount {
    int convex = 0, concave = 0;
};

struct TrialResult {
    FollowingMode mode = FollowingMode::Active;
    TrialEnd end = TrialEnd::TapCap;
    std::string detail;  ///< the sentence behind `end`
    std::vector<FollowedTap> taps;
    double robotTime_s = 0.0;
    /// Fraction of the contour within the contact patch's reach (core/geometry/ContourReach.h),
    /// and of that part, the fraction with a tap within the coverage radius.
    double reachable = 1.0;
    double coverage = 0.0;
    double meanContourDistance_mm = 0.0;
    double maxContourDistance_mm = 0.0;
    double progress_mm = 0.0;
    /// The furthest the tip got along the contour (the largest progress of any tap), and that
    /// place on the outline: where a trial that did not complete was last making headway.
    double furthestProgress_mm = 0.0;
    ContourPlace furthest;
    /// Corners the tip got round: went past by more than the reach (every corner, once, for a
    /// completed trial).
    CornerCount cornersRounded;

    bool completed() const { return end == TrialEnd::Completed; }
    /// Did not complete, and got no further than near a corner.
    bool stoppedAtCorner() const {
        return !completed() && furthest.kind != PlaceKind::AwayFromCorners;
    }
    std::vector<Vec2> path() const;
};

struct TrialSetup {
    FollowingMode mode = FollowingMode::Active;
    Vec2 start;
    double startEdgeDeg = 270.0;  ///< the edge the tip starts on (memory's first edge)
    FollowingSettings settings;
    ValidOffsets valid;
    double noiseFloor = 1.0;
    /// How each tap's evidence enters a sequential belief (a belief threshold above 0) with the
    /// discrete percept: the run's calibration of one tap's belief. The identity leaves the
    /// naive-Bayes log-likelihoods as they are.
    BeliefScaling beliefScaling;
    /// The contact patch's radius on an edge (FingertipContactModel::edgeContactRadius): the
    /// contour it cannot resolve does not count toward coverage. 0: every point counts.
    double contactRadius_mm = 0.0;
};

/// The start pose the paper uses: on the lower edge (the one facing most nearly down, the lowest
/// of equals), at its middle, centred in the valid range. Throws std::invalid_argument for an
/// outline without edges.
Vec2 lowerEdgeStart(const Polygon& outline, const ValidOffsets& valid);

/// How far past the outline a trial's tip can reach: it counts as lost once more than
/// lost_outside_mm outside, and the move that took it there is at most the largest pair of
/// steps one rule combines.
double followingReach_mm(const FollowingSettings& s);

/// Why a trial on `outline` could drive the stage past its travel (0..travel_mm) before it
/// counts as lost, naming the side ("the left side (x = 0)"), or empty.
std::string followingTravelProblem(const Polygon& outline, const FollowingSettings& s,
                                   Vec2 travel_mm);

/// Why `start` cannot begin a trial on `outline` (too far from the contour), or empty.
std::string startProblem(const Polygon& outline, Vec2 start, const FollowingSettings& settings);

/// Runs one trial. `onTap` sees each tap as it is taken (for the recording) and may return false
/// to cancel. A device error ends the trial with TrialEnd::DeviceError and its message (a replayed
/// recording that holds no tap for where the trial went: TrialEnd::LeftRecording); every tap taken
/// so far is kept.
TrialResult runTrial(Rig& rig, const HistogramClassifier& classifier, const ClassSet& classes,
                     const Polygon& outline, const TrialSetup& setup,
                     const std::function<bool(const FollowedTap&)>& onTap = {});

/// Where the trial got furthest and which corners it got round, from its taps' progress;
/// `startArc` is the arc length of the start pose's nearest outline point.
void judgePlaces(const Polygon& outline, double startArc, const CornerCriteria& criteria,
                 TrialResult& result);

/// Coverage and contour distances of a path against an outline: coverage over the part of the
/// contour a patch of `contactRadius` can resolve (all of it for 0).
void measurePath(const Polygon& outline, const std::vector<Vec2>& path, double coverageRadius,
                 double contactRadius, TrialResult& result);

}  // namespace activetouch
