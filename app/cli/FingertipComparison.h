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
    /// The 50th, 90th and 99th percentiles of the readings over kPressed_counts of the scene's
    /// fingertip tapping across its object's edge (all taxels together).
    std::vector<double> pressedQuantiles;
};

/// Readings over this many counts above rest are pressed, for the quantiles under contact.
inline constexpr double kPressed_counts = 3.0;
inline constexpr double kPressedLevels[] = {0.5, 0.9, 0.99};

/// The quantiles at kPressedLevels of the finger's readings over kPressed_counts above rest in
/// frames not at rest (all its taxels together); empty if none.
std::vector<double> realPressedQuantiles(const FingertipStatsReport& report,
                                         const std::string& finger);

/// The taxels of `finger` in `report`, in order. Throws InputError naming the finger and those
/// the report has.
std::vector<const TaxelStats*> taxelsOf(const FingertipStatsReport& report,
                                        const std::string& finger);

/// Compares `finger`'s resting readings with each scene's simulated fingertip at rest (taxel k
/// with taxel k; the scene's fingertip must have as many taxels as the finger).
std::vector<SceneComparison> compareWithScenes(const FingertipStatsReport& report,
                                               const std::string& finger,
                                               const std::vector<std::string>& scenePaths);

void printComparison(const std::vector<SceneComparison>& comparisons, const std::string& finger,
                     const std::vector<double>& realPressed);

/// `baseScene` (a scene document) with the effects `finger`'s statistics call for and where
/// they came from.
Json measuredScene(const Json& baseScene, const FingertipStatsReport& report,
                   const std::string& finger, const std::string& provenance);

}  // namespace activetouch::cli
