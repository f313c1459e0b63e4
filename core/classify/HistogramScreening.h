#pragma once
// What the classifier's training (HistogramClassifier.cpp) and its per-tap scoring
// (HistogramScoring.cpp) share about the screening table. Internal to core/classify.
#include <cstddef>

namespace activetouch::screening {

// The screening table's largest level: a row's half-range maps to +-32767.
inline constexpr double kScreenLevels = 32767.0;
// Screening sums stay exact in 32 bits while a tap has at most this many samples (each a count
// times a level of at most 32767 in magnitude); longer taps are summed exactly throughout.
inline constexpr std::size_t kMaxScreenSamples = 32767;

}  // namespace activetouch::screening
