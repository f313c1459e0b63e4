#pragma once
// Which region (plane, edge, air) each class's taps belong to, computed once from the fingertip
// geometry (DESIGN.md §2): tap the ideal fingertip at the class's offset from a straight edge;
// plane = the whole pressed patch lies on the object, air = no taxel above the noise floor,
// edge = the rest. A tilted tip is not symmetric, so the map differs by orientation.
#include <vector>

#include "core/fingertip/FingertipContactModel.h"
#include "core/scene/Scene.h"
#include "core/tap/ClassSet.h"

namespace activetouch {

std::vector<Region> computeClassRegions(const FingertipContactModel& model, const ClassSet& classes,
                                        const TapSpec& tap, double strokeLimitDepth);

}  // namespace activetouch
