#pragma once
// The settings of the perception-action loop and of a trial's termination (docs/design.md §3).
// Every step length of the rules table is one of these numbers.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace activetouch {

enum class FollowingMode { Active, Passive };
const char* modeName(FollowingMode m);
/// The mode `name` names ("active" or "passive", as modeName gives them), if it names one.
std::optional<FollowingMode> modeNamed(std::string_view name);

/// What the loop reads from a tap: the winning class (the paper), or an edge angle and position
/// on a continuum from the whole posterior (core/classify/ContinuousEdge.h).
enum class PerceptKind { Discrete, Continuous };
const char* perceptKindName(PerceptKind k);  ///< "discrete", "continuous"
std::optional<PerceptKind> perceptKindNamed(std::string_view name);

struct FollowingSettings {
    PerceptKind percept = PerceptKind::Discrete;
    /// Continuous percept: each class's log-likelihood is divided by this before the posterior is
    /// formed; 0 takes the tap's samples per taxel (a mean log-likelihood per sample instant).
    double perceptTemperature = 0.0;
    /// Continuous percept: the turn of the contour per mm is estimated from the angles of the
    /// last this many edge percepts, and the follow direction is turned by the turn expected over
    /// half a step (0 = no anticipation, the default: docs/general-shapes.md measures it neutral
    /// at 2 mm steps and harmful at 5 mm).
    int curvatureTaps = 0;
    /// Continuous percept: edge angles within this many degrees count as the same edge for
    /// edge_confirmation_taps.
    double sameEdgeTolerance_deg = 20.0;
    double followStep_mm = 2.0;      ///< along the perceived edge, every tap (paper: 2 mm)
    double repositionStep_mm = 1.0;  ///< along the edge normal toward the valid range (paper: 1 mm)
    double planeStep_mm = 2.0;  ///< active, plane percept: outward along the last edge's normal
    double planeRetreatStep_mm = 2.0;  ///< active, plane percept: back against the last heading
    double airInwardStep_mm = 2.0;     ///< active, air percept: inward along the last edge's normal
    double airRetreatStep_mm = 2.0;    ///< active, air percept: back against the last heading
    /// Active mode uses a percept's orientation only at positions whose mean angle error in the
    /// validation is at most this (degrees); 180 trusts every edge percept, as the paper does.
    double orientationTrustMaxError_deg = 30.0;
    /// Active mode: same-orientation edge percepts in a row before memory takes the edge as the
    /// last edge (1 = at once; passive mode always uses 1, as the paper's heading rule does).
    int edgeConfirmationTaps = 2;
    /// Sequential perception: 0 decides from each tap alone (the paper); a value in (0, 1) taps
    /// again at the same place, accumulating evidence, until the belief's largest posterior
    /// reaches it or maxTapsPerDecision taps were taken.
    double beliefThreshold = 0.0;
    int maxTapsPerDecision = 5;
    /// The evidence a sequential belief accumulates with the discrete percept. Calibrated (the
    /// default): each tap's log-likelihoods scaled by the run's sequential factor (its
    /// belief_calibration), and the plane classes, like the air classes, decided on as one
    /// percept, since the tip cannot tell them apart. Naive Bayes: the log-likelihoods as they
    /// are, deciding on the single most likely class; one tap's posterior is then already near 1,
    /// so thresholds act only very near 1.
    bool calibratedBelief = true;
    /// While gathering evidence, reposition toward the valid range between taps (active mode).
    bool repositionWhileSensing = false;
    // Termination.
    double completionRadius_mm = 4.0;  ///< back within this of the start after a full perimeter
    double lostOutside_mm = 10.0;      ///< lost when this far outside the contour
    double lostInside_mm = 6.0;        ///< lost when this far inside the object
    int lostPlaneOrAirTaps = 6;        ///< lost after this many plane/air decisions in a row
    double tapCapPerimeters = 3.0;     ///< tap cap = this x perimeter / follow step
    double coverageRadius_mm = 3.0;    ///< a perimeter point is covered by a tap this close

    std::string problem() const;
    /// Whether a trial reads the run's belief calibration: a sequential discrete percept on the
    /// calibrated belief (its sequential factor scales each tap's evidence).
    bool readsBeliefCalibration() const {
        return beliefThreshold > 0.0 && calibratedBelief && percept != PerceptKind::Continuous;
    }
};

/// A number of the following settings as an experiment file gives it ("following": {key: ...}):
/// its key, the range a file may give, and the setting it sets.
struct FollowingNumber {
    const char* key;
    double lo, hi;
    double FollowingSettings::*member;
};
/// Every number of the following settings, in the order files list them.
const std::vector<FollowingNumber>& followingNumbers();

}  // namespace activetouch
