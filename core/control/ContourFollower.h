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

#include "core/classify/HistogramClassifier.h"
#include "core/control/DecisionRules.h"
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

struct TrialResult {
    FollowingMode mode = FollowingMode::Active;
    TrialEnd end = TrialEnd::TapCap;
    std::string detail;  ///< the sentence behind `end`
    std::vector<FollowedTap> taps;
    double robotTime_s = 0.0;
    double coverage = 0.0;  ///< fraction of the perimeter with a tap within the coverage radius
    double meanContourDistance_mm = 0.0;
    double maxContourDistance_mm = 0.0;
    double progress_mm = 0.0;

    bool completed() const { return end == TrialEnd::Completed; }
    std::vector<Vec2> path() const;
};

struct TrialSetup {
    FollowingMode mode = FollowingMode::Active;
    Vec2 start;
    double startEdgeDeg = 270.0;  ///< the edge the tip starts on (memory's first edge)
    FollowingSettings settings;
    ValidOffsets valid;
    double noiseFloor = 1.0;
};

/// The start pose the paper uses: on the lower edge (the one facing most nearly down, the lowest
/// of equals), at its middle, centred in the valid range. Throws std::invalid_argument if no
/// edge faces within 45 degrees of down.
Vec2 lowerEdgeStart(const Polygon& outline, const ValidOffsets& valid);

/// Why `start` cannot begin a trial on `outline` (too far from the contour), or empty.
std::string startProblem(const Polygon& outline, Vec2 start, const FollowingSettings& settings);

/// Runs one trial. `onTap` sees each tap as it is taken (for the recording) and may return false
/// to cancel. A device error ends the trial with TrialEnd::DeviceError and its message (a replayed
/// recording that holds no tap for where the trial went: TrialEnd::LeftRecording); every tap taken
/// so far is kept.
TrialResult runTrial(Rig& rig, const HistogramClassifier& classifier, const ClassSet& classes,
                     const Polygon& outline, const TrialSetup& setup,
                     const std::function<bool(const FollowedTap&)>& onTap = {});

/// Coverage and contour distances of a path against an outline.
void measurePath(const Polygon& outline, const std::vector<Vec2>& path, double coverageRadius,
                 TrialResult& result);

}  // namespace activetouch
