#pragma once
// Physical bounds every file is held to (docs/limits.md): values beyond them describe no rig, so
// they are refused by place instead of being carried into arithmetic that loses precision.

namespace activetouch {

/// The longest stage travel a scene may give, mm per axis: about three times the longest axis
/// of a common lab XY stage, and far inside where millimetre arithmetic loses precision.
inline constexpr double kMaxStageTravel_mm = 2000.0;
/// The most samples a tap may have: a 200 s tap window at 50 Hz, far beyond any tap.
inline constexpr int kMaxTapSamples = 10000;

/// The most taxels a fingertip may have: a whole iCub hand's skin vector is 192.
inline constexpr int kMaxTaxels = 1024;
/// The most edge orientations an experiment may list: one per degree.
inline constexpr int kMaxOrientations = 360;
/// The most values one accuracy-versus-time sweep may list.
inline constexpr int kMaxSweepValues = 64;

}  // namespace activetouch
