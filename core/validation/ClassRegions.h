#pragma once
// Which region (plane, edge, air) each class's taps belong to (docs/design.md §3): tap the ideal
// fingertip at the class's offset from a straight edge; plane = the whole pressed patch lies on
// the object, air = no taxel above the noise floor, edge = the rest. A tilted tip is not
// symmetric, so the map differs by orientation.
//
// The noise floor is a tap's: the highest reading a tap that touches nothing shows. A tap is 50
// samples of 12 taxels, so its peak over pure noise lies well above a single sample's noise (about
// 3 sigma of the taxel noise), and a class whose ideal peak pressure stays below that floor cannot
// be told from air. The floor is measured from the run's own taps at the classes whose ideal tap
// touches nothing, and never taken below the scene's `noise_floor_counts`.
#include <optional>
#include <vector>

#include "core/fingertip/FingertipContactModel.h"
#include "core/scene/Scene.h"
#include "core/tap/ClassSet.h"
#include "core/tap/Tap.h"

namespace activetouch {

/// The ideal tap of one class: its largest taxel pressure, counts, and whether its whole pressed
/// patch lies on the object.
struct IdealClassContact {
    double peak = 0.0;
    bool fullyOnObject = false;
};

/// Each class's ideal tap, computed once from the fingertip geometry.
std::vector<IdealClassContact> idealClassContacts(const FingertipContactModel& model,
                                                  const ClassSet& classes, const TapSpec& tap,
                                                  double strokeLimitDepth);

/// The region map for a given noise floor (counts).
std::vector<Region> classRegions(const std::vector<IdealClassContact>& contacts, double noiseFloor);

/// The region map with the scene's noise floor.
std::vector<Region> computeClassRegions(const FingertipContactModel& model, const ClassSet& classes,
                                        const TapSpec& tap, double strokeLimitDepth);

struct MeasuredNoiseFloor {
    double counts = 0.0;  ///< the 95th percentile of the no-contact taps' peak readings
    int taps = 0;         ///< how many no-contact taps it was measured from
};

struct ClassTap {
    int cls;
    const Tap* tap;
};

/// The tap-level noise floor measured from `taps` at the classes whose ideal tap presses no taxel
/// at all (nearest-rank 95th percentile of their peak readings); nothing when there is no such tap
/// (a class set that never leaves the object).
std::optional<MeasuredNoiseFloor> measureNoiseFloor(const std::vector<IdealClassContact>& contacts,
                                                    const std::vector<ClassTap>& taps);

}  // namespace activetouch
