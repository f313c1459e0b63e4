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

    /// "lower edge", "upper edge", "left edge", "right edge", "plane" or "air".
    std::string shapeClass() const;
};

Percept perceive(const HistogramClassifier& classifier, const ClassSet& classes, const Tap& tap);
/// The percept that class `cls` stands for, with its posterior.
Percept perceptOf(int cls, double posterior, const ClassSet& classes);

}  // namespace activetouch
