#pragma once
// The runs between which every figure a run writes is drawn: the paper (Figures 5-9), the
// accuracy-versus-time sweeps, and the continuous percept on 648 classes following two of the
// general shapes once.
#include <vector>

#include "core/run/ExperimentRun.h"
#include "support/Paths.h"
#include "support/SimulatedRun.h"

namespace activetouch::test {

inline std::vector<RunResult> figureRuns() {
    std::vector<RunResult> runs;
    for (const char* file : {"experiments/paper.json", "experiments/accuracy_vs_time.json"})
        runs.push_back(runExperiment(loadExperiment(sourcePath(file)), onSimulatedRig()));
    ExperimentSpec general = loadExperiment(sourcePath("experiments/general_shapes.json"));
    general.trials.resize(2);
    for (TrialSpec& t : general.trials) t.repeats = 1;
    runs.push_back(runExperiment(general, onSimulatedRig()));
    return runs;
}

}  // namespace activetouch::test
