#include "core/control/ControllerRange.h"

namespace activetouch {

ControllerRange controllerRange(const ClassSet& classes, const ValidationResult& validation,
                                double trustMaxError_deg) {
    ControllerRange r;
    const double half = 0.5 * classes.positionStep_mm;
    r.offsets.low = classes.offsetOf(validation.validRange.first) - half;
    r.offsets.high = classes.offsetOf(validation.validRange.last) + half;
    const auto& angle = validation.angleMean;
    int lo = validation.validRange.first, hi = validation.validRange.last;
    if (trustMaxError_deg >= 180.0) {
        lo = 1;
        hi = classes.positions;
    } else {
        while (lo > 1 && angle[static_cast<std::size_t>(lo - 2)] <= trustMaxError_deg) --lo;
        while (hi < classes.positions && angle[static_cast<std::size_t>(hi)] <= trustMaxError_deg)
            ++hi;
    }
    r.trustedPositions = {lo, hi};
    r.offsets.trustedLow = classes.offsetOf(lo) - half;
    r.offsets.trustedHigh = classes.offsetOf(hi) + half;
    return r;
}

}  // namespace activetouch
