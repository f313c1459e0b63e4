// Microseconds to classify one tap (72 classes, T = 50, K = 12) with a classifier trained on the
// paper scene's data set 1. Budget (DESIGN.md §7): <= 2 us on one core.
#include <cstdio>

#include "app/run/ExperimentRun.h"
#include "bench/BenchHarness.h"
#include "core/experiment/Experiment.h"

using namespace activetouch;

int main(int argc, char** argv) {
    const std::string experiment = argc > 1 ? argv[1] : std::string(ACTIVETOUCH_SOURCE_DIR) + "/experiments/paper.json";
    const ExperimentSpec spec = loadExperiment(experiment);
    const RunResult run = runExperiment(spec, {});
    std::vector<const Tap*> tests;
    for (const auto& t : run.taps)
        if (!spec.training.isTrainingSet(t.dataSet)) tests.push_back(&t.record.tap);
    std::size_t i = 0;
    int sink = 0;
    const double us = bench::medianMicroseconds([&] { sink += run.classifier.classify(*tests[i++ % tests.size()]); }, 20000);
    bench::report("classify one tap (72 classes, T=50, K=12)", us, "us", 2.0);
    return sink == -1;
}
