#pragma once
// Real fingertips beside simulated ones (docs/real-fingertips.md): each taxel's resting readings
// against a scene's simulated fingertip at rest, by the Kolmogorov-Smirnov distance, and the
// scene those statistics call for.
#include <string>
#include <vector>

#include "core/analysis/FingertipStats.h"

namespace activetouch::cli {

struct SceneComparison {
    std::string scene;
    double sigma = 0.0;      ///< the scene's taxel_noise, counts (0: it lists none)
    std::vector<double> ks;  ///< per taxel of the finger compared
};

/// The taxels of `finger` in `report`, in order. Throws InputError naming the finger and those
/// the report has.
std::vector<const TaxelStats*> taxelsOf(const FingertipStatsReport& report,
                                        const std::string& finger);

/// Compares `finger`'s resting readings with each scene's simulated fingertip at rest (taxel k
/// with taxel k; the scene's fingertip must have as many taxels as the finger).
std::vector<SceneComparison> compareWithScenes(const FingertipStatsReport& report,
                                               const std::string& finger,
                                               const std::vector<std::string>& scenePaths);

void printComparison(const std::vector<SceneComparison>& comparisons, const std::string& finger);

/// `baseScene` (a scene document) with the effects `finger`'s statistics call for and where
/// they came from.
Json measuredScene(const Json& baseScene, const FingertipStatsReport& report,
                   const std::string& finger, const std::string& provenance);

}  // namespace activetouch::cli
