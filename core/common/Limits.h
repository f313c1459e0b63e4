#pragma once
// Physical bounds every file is held to (docs/limits.md): values beyond them describe no rig, so
// they are refused by place instead of being carried into arithmetic that loses precision.

namespace activetouch {

/// The longest stage travel a scene may give, mm per axis: about three times the longest axis
/// of a common lab XY stage, and far inside where millimetre arithmetic loses precision.
inline constexpr double kMaxStageTravel_mm = 2000.0;
/// The most samples a tap may have: a 200 s tap window at 50 Hz, far beyond any tap.
inline constexpr int kMaxTapSamples = 10000;

}  // namespace activetouch
