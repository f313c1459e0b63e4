#pragma once
// The recognition step of the experiment (docs/design.md §4): a template per shape from an ideal
// follower's path, and each traced path named after its nearest template.
#include <string>
#include <vector>

#include "core/geometry/Polygon.h"
#include "core/recognition/PathHistogram.h"

namespace activetouch {

struct NamedOutline {
    std::string shape;
    const Polygon* outline = nullptr;  ///< not owned
};

/// One template per distinct shape name (the first outline of each name counts): where a perfect
/// follower would tap at `offset_mm` from the edge every `step_mm`, averaged over where along the
/// outline it starts, as a `bins` x `bins` histogram, raw and smoothed by `sigmaBins`.
std::vector<ShapeTemplate> shapeTemplates(const std::vector<NamedOutline>& shapes,
                                          double offset_mm, double step_mm, int bins,
                                          double sigmaBins);

}  // namespace activetouch
