// Figure 6 recorded beside Figure 6 simulated with the fitted scene (SceneFit.h).
#include "devices/simulated/fit/FitParts.h"

namespace activetouch {

Figure6Comparison compareFigure6(const ExperimentSpec& spec, const std::vector<CollectedTap>& taps,
                                 const SceneFit& fit) {
    auto validationOf = [&](const std::vector<CollectedTap>& recorded) {
        RunOptions options;
        options.simulated = &simulatedRigs();
        options.recordedTaps = &recorded;
        return runExperiment(spec, options).validation;
    };
    Figure6Comparison c;
    c.recorded = validationOf(taps);
    std::vector<CollectedTap> simulated = taps;
    for (std::size_t r = 0; r < fit.simulated.size(); ++r) {
        for (std::size_t i = 0; i < simulated.size(); ++i) {
            simulated[i].record.tap = fit.simulated[r][i].tap;
            simulated[i].record.ending = fit.simulated[r][i].ending;
        }
        if (r == 0) c.firstSimulated = simulated;
        c.simulated.push_back(validationOf(simulated));
    }
    if (c.simulated.empty()) return c;
    c.angleLeast = c.positionLeast = 1e300;
    c.angleLargest = c.positionLargest = -1e300;
    for (const auto& v : c.simulated) {
        c.angleMean += v.angleError_deg / static_cast<double>(c.simulated.size());
        c.positionMean += v.positionError_mm / static_cast<double>(c.simulated.size());
        c.angleLeast = std::min(c.angleLeast, v.angleError_deg);
        c.angleLargest = std::max(c.angleLargest, v.angleError_deg);
        c.positionLeast = std::min(c.positionLeast, v.positionError_mm);
        c.positionLargest = std::max(c.positionLargest, v.positionError_mm);
    }
    c.recordedInsideRange = c.recorded.angleError_deg >= c.angleLeast &&
                            c.recorded.angleError_deg <= c.angleLargest &&
                            c.recorded.positionError_mm >= c.positionLeast &&
                            c.recorded.positionError_mm <= c.positionLargest;
    return c;
}

}  // namespace activetouch
