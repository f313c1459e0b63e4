#pragma once
// The training protocol (docs/design.md §3, paper §3.1): at the middle of each edge of the training
// object, tap at every position across the edge; one data set = one tap per class (or several).
// Sets are numbered from 1; some train, the rest test. Test sets may be shifted off the training
// grid so validation does not overstate accuracy. Between sets the object is re-placed with a
// small random displacement (placement jitter).
#include <functional>
#include <vector>

#include "core/common/Random.h"
#include "core/geometry/Polygon.h"
#include "core/rig/Rig.h"
#include "core/tap/ClassSet.h"

namespace activetouch {

struct TrainingProtocolSettings {
    int dataSets = 5;
    std::vector<int> trainingSets{1};  ///< 1-based set numbers; the others test
    int tapsPerClass = 1;
    double testOffset_mm = 0.0;       ///< test taps shifted along the edge normal
    double placementJitter_mm = 0.2;  ///< per-set object displacement, standard deviation per axis
    /// After validation, train the classifier the trials follow with again on every data set,
    /// test sets included: the validation (errors, valid range, trusted span) still comes from the
    /// training sets against the test sets, but the loop gets every tap the protocol took. Test
    /// sets shifted off the grid (testOffset_mm) then train their classes at that shift.
    bool retrainOnAllSets = false;

    bool isTrainingSet(int set) const;
    /// Why the settings cannot run, or empty.
    std::string problem() const;
};

struct CollectedTap {
    TapRecord record;
    int dataSet = 1;
    int cls = 0;
    double trueOffset_mm = 0.0;  ///< tip centre's signed distance from the edge, as commanded
};

/// Where each orientation's taps are taken: the middle of the longest edge of the training
/// object whose outward normal points that way.
struct EdgeSite {
    Vec2 midpoint;
    Vec2 normal;
    /// The tip pose at signed distance `offset_mm` from the edge along its outward normal.
    Vec2 poseAt(double offset_mm) const { return midpoint + offset_mm * normal; }
    /// The signed distance of a tip pose from the edge along its outward normal: the true offset
    /// of a tap taken there, whether the pose came from the protocol or from a stage's log.
    double offsetOf(Vec2 pose) const { return dot(pose - midpoint, normal); }
};
/// Throws std::invalid_argument if the object has no edge for an orientation.
std::vector<EdgeSite> edgeSites(const Polygon& object, const ClassSet& classes);

/// Why the protocol's taps cannot all be taken as meant, or empty: no edge for an orientation
/// (see edgeSites), a position on the plane side that lies past the object's far side (it would
/// train a plane class on air), or a tap pose (training or shifted test, with 4 standard
/// deviations of placement jitter) outside the stage travel 0..travel_mm.
std::string trainingPosesProblem(const Polygon& object, const ClassSet& classes,
                                 const TrainingProtocolSettings& settings, Vec2 travel_mm);

/// Runs the protocol on `rig`. `onTap` sees every tap as it is taken (for the run's recording)
/// and may return false to stop early; the taps collected so far are returned.
std::vector<CollectedTap> collectTrainingTaps(
    Rig& rig, const Polygon& object, const ClassSet& classes,
    const TrainingProtocolSettings& settings, RandomStream rng,
    const std::function<bool(const CollectedTap&)>& onTap = {});

}  // namespace activetouch
