#pragma once
// What a scene's simulated fingertip reads at rest (docs/real-fingertips.md): taps in the air,
// clear of the object, so that every sample is the scene's signal effects alone.
#include <vector>

#include "core/scene/Scene.h"

namespace activetouch {

struct RestingReadings {
    int samplesPerTap = 0;
    std::vector<std::vector<double>> taxels;  ///< per taxel, every sample of every tap in turn
};

/// The readings of `taps` taps taken 30 mm clear of the scene's object, in counts as the
/// simulated fingertip reports them.
RestingReadings restingReadings(const SceneSpec& scene, int taps);

/// The readings of taps across the scene's object's lowest edge (at its middle, every half
/// millimetre from 6 mm outside to 6 mm inside, `rounds` times over): what its fingertip reads
/// under contact, per taxel, every sample.
std::vector<std::vector<double>> edgeReadings(const SceneSpec& scene, int rounds);

}  // namespace activetouch
