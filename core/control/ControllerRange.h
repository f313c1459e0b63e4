#pragma once
// Where the controller trusts a percept, derived from offline validation (docs/design.md §3-4):
// the valid range it repositions into, and the wider span of positions whose perceived
// orientation it follows.
#include <utility>

#include "core/control/DecisionRules.h"
#include "core/tap/ClassSet.h"
#include "core/validation/OfflineValidation.h"

namespace activetouch {

struct ControllerRange {
    ValidOffsets offsets;  ///< valid range and trusted span as offsets from the edge, mm
    std::pair<int, int> trustedPositions{1, 1};  ///< first and last trusted class position
};

/// The valid range is the span of the validated range's class positions, half a position step
/// wide on each side. The trusted span grows from the valid range outwards over every adjacent
/// position whose mean angle error is at most `trustMaxError_deg`; 180 or more trusts them all.
ControllerRange controllerRange(const ClassSet& classes, const ValidationResult& validation,
                                double trustMaxError_deg);

}  // namespace activetouch
