#pragma once
// One tap: T samples x K taxels of pressure (counts, 0 = no contact), aligned to the tap start,
// with where and when it was taken.
#include <cstddef>
#include <vector>

#include "core/geometry/Vec2.h"

namespace activetouch {

inline constexpr int kSamplesPerTap = 50;    ///< T: 1 s at 50 Hz (docs/design.md §3)
inline constexpr int kFingertipTaxels = 12;  ///< K
inline constexpr double kSampleRateHz = 50.0;

struct Tap {
    int taxels = kFingertipTaxels;
    std::vector<double> samples;  ///< sample-major: samples[t * taxels + k]

    Tap() = default;
    Tap(int sampleCount, int taxelCount)
        : taxels(taxelCount), samples(static_cast<std::size_t>(sampleCount * taxelCount), 0.0) {}

    int sampleCount() const { return taxels > 0 ? static_cast<int>(samples.size()) / taxels : 0; }
    double at(int t, int k) const { return samples[static_cast<std::size_t>(t * taxels + k)]; }
    double& at(int t, int k) { return samples[static_cast<std::size_t>(t * taxels + k)]; }
    const double* frame(int t) const {
        return samples.data() + static_cast<std::size_t>(t * taxels);
    }
    double* frame(int t) { return samples.data() + static_cast<std::size_t>(t * taxels); }
};

/// How the tapper's stroke ended.
enum class TapEnding { ContactReflex, StrokeLimit };

/// A tap with its context: where the stage was, when it started on the robot clock, and how the
/// tapper stopped.
struct TapRecord {
    Tap tap;
    Vec2 pose;                 ///< commanded fingertip centre, mm
    double startTime_s = 0.0;  ///< robot time at tap start
    double cycleTime_s = 0.0;  ///< tap window plus settle time
    TapEnding ending = TapEnding::StrokeLimit;
    double stopDepth_mm = 0.0;  ///< indentation where the stroke stopped (0 = no contact)
};

}  // namespace activetouch
