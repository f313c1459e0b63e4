// Microseconds to classify one tap (72 classes, T = 50, K = 12) with a classifier trained on the
// paper scene's data set 1. Budget (docs/benchmarks.md): <= 2 us on one core.
#include <cstdio>

#include "core/run/ExperimentRun.h"
#include "bench/BenchHarness.h"
#include "core/classify/SequentialPerception.h"
#include "core/experiment/Experiment.h"
#include "support/SimulatedRun.h"

using namespace activetouch;

int main(int argc, char** argv) {
    const std::string experiment =
        argc > 1 ? argv[1] : std::string(ACTIVETOUCH_SOURCE_DIR) + "/experiments/paper.json";
    const ExperimentSpec spec = loadExperiment(experiment);
    const RunResult run = runExperiment(spec, test::onSimulatedRig());
    std::vector<const Tap*> tests;
    for (const auto& t : run.taps)
        if (!spec.training.isTrainingSet(t.dataSet)) tests.push_back(&t.record.tap);
    std::size_t i = 0;
    int sink = 0;
    const double us = bench::medianMicroseconds(
        [&] { sink += run.classifier.classify(*tests[i++ % tests.size()]); }, 20000);
    bench::report("classify one tap (72 classes, T=50, K=12)", us, "us", 2.0);
    // A sequential update: one tap's log-likelihoods into the belief, renormalised. (The budget
    // is that of a decision: a tap's classification plus its update should stay within 2 us.)
    SequentialBelief belief(run.classes);
    std::vector<double> ll(static_cast<std::size_t>(run.classes.classCount()));
    run.classifier.logLikelihoods(*tests.front(), ll.data());
    for (double& v : ll) v *= 1e-3;  // keep the belief from saturating over the repetitions
    const double update = bench::medianMicroseconds([&] { belief.update(ll.data()); }, 20000);
    bench::report("sequential update of the belief (72 classes)", update, "us", 2.0);
    return sink == -1;
}
