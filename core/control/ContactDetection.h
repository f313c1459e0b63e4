#pragma once
// Contact detection (paper §2.3, Figure 4): the tapper's reflex stops the stroke when the
// fingertip's total pressure crosses the contact threshold, so objects of any height are tapped
// alike. The reflex itself runs inside each Tapper (simulated or NXT), next to the motor; this
// unit says what the loop learns from it.
#include <algorithm>

#include "core/tap/Tap.h"

namespace activetouch {

/// Whether a tap touched anything: the reflex fired, or some taxel rose above the noise floor
/// before the stroke limit (a partial contact near an edge).
inline bool contactMade(const TapRecord& r, double noiseFloor) {
    if (r.ending == TapEnding::ContactReflex) return true;
    return !r.tap.samples.empty() &&
           *std::max_element(r.tap.samples.begin(), r.tap.samples.end()) > noiseFloor;
}

}  // namespace activetouch
