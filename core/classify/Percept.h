#pragma once
// What one tap is perceived as: the classifier's winning class read as a shape class, an edge
// orientation and a position across the edge (docs/design.md §3).
#include <string>

#include "core/classify/HistogramClassifier.h"
#include "core/tap/ClassSet.h"

namespace activetouch {

/// The percept of one tap: the winning class read as (shape class, orientation, position).
struct Percept {
    int cls = 0;
    Region region = Region::Edge;  ///< plane / edge / air; an edge carries its orientation
    double orientationDeg = 0.0;
    int position = 1;        ///< class position, 1..positions
    double offset_mm = 0.0;  ///< perceived signed distance of the tip centre from the edge
    double posterior = 0.0;
    /// A continuous percept: the orientation and offset above come from the whole posterior
    /// (core/classify/ContinuousEdge.h) rather than from the winning class; `position` is then
    /// the nearest class position and `concentration` the normals' mean resultant length.
    bool continuous = false;
    double concentration = 1.0;

    /// "lower edge", "upper edge", "left edge", "right edge", "plane" or "air".
    std::string shapeClass() const;
};

Percept perceive(const HistogramClassifier& classifier, const ClassSet& classes, const Tap& tap);
/// The continuous percept of one tap: the winning class's region, and for an edge the angle and
/// offset from the posterior of log-likelihoods / `temperature` (> 0). Where the posterior gives
/// no angle (the edge weight cancels out), the winning class's orientation and position stand.
Percept perceiveContinuous(const ClassSet& classes, const double* logLikelihoods,
                           double temperature);
/// The temperature a continuous percept uses: `setting`, or where it is 0 the tap's samples per
/// taxel.
double perceptTemperatureFor(double setting, const Tap& tap);
/// The percept that class `cls` stands for, with its posterior.
Percept perceptOf(int cls, double posterior, const ClassSet& classes);

}  // namespace activetouch
