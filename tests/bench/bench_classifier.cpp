// Microseconds to classify one tap with a classifier trained on data set 1: the paper's 72 classes
// (T = 50, K = 12), and general_shapes.json's 648 (36 orientations x 18 positions), there also
// with the continuous percept; and recognising a traced path at any pose among that experiment's
// twelve shapes. Budgets (docs/benchmarks.md): 1 us at 72 classes, 8 us at 648, 1 ms a path.
#include <cstdio>

#include "bench/BenchHarness.h"
#include "core/classify/Percept.h"
#include "core/classify/SequentialPerception.h"
#include "core/experiment/Experiment.h"
#include "core/recognition/PoseRecognition.h"
#include "core/run/ExperimentRun.h"
#include "support/SimulatedRun.h"

using namespace activetouch;

int main(int argc, char** argv) {
    const std::string experiment =
        argc > 1 ? argv[1] : std::string(ACTIVETOUCH_SOURCE_DIR) + "/experiments/paper.json";
    bench::reportClock("this machine's clock, at the start");
    const ExperimentSpec spec = loadExperiment(experiment);
    const RunResult run = runExperiment(spec, test::onSimulatedRig());
    std::vector<const Tap*> tests;
    for (const auto& t : run.taps)
        if (!spec.training.isTrainingSet(t.dataSet)) tests.push_back(&t.record.tap);
    std::size_t i = 0;
    int sink = 0;
    const double us = bench::medianMicroseconds(
        [&] { sink += run.classifier.classify(*tests[i++ % tests.size()]); }, 20000);
    bench::report("classify one tap (72 classes, T=50, K=12)", us, "us", 1.0);
    // A sequential update: one tap's log-likelihoods into the belief, renormalised. (The budget
    // is that of a decision: a tap's classification plus its update should stay within 2 us.)
    SequentialBelief belief(run.classes);
    std::vector<double> ll(static_cast<std::size_t>(run.classes.classCount()));
    run.classifier.logLikelihoods(*tests.front(), ll.data());
    for (double& v : ll) v *= 1e-3;  // keep the belief from saturating over the repetitions
    const double update = bench::medianMicroseconds([&] { belief.update(ll.data()); }, 20000);
    bench::report("sequential update of the belief (72 classes)", update, "us", 2.0);

    // 648 classes, and recognition at any pose, on general_shapes.json's run.
    const ExperimentSpec general =
        loadExperiment(std::string(ACTIVETOUCH_SOURCE_DIR) + "/experiments/general_shapes.json");
    const RunResult g = runExperiment(general, test::onSimulatedRig());
    std::vector<const Tap*> gTests;
    for (const auto& t : g.taps)
        if (!general.training.isTrainingSet(t.dataSet)) gTests.push_back(&t.record.tap);
    i = 0;
    const double us648 = bench::medianMicroseconds(
        [&] { sink += g.classifier.classify(*gTests[i++ % gTests.size()]); }, 5000);
    bench::report("classify one tap (648 classes, T=50, K=12)", us648, "us", 8.0);
    std::vector<double> gl(static_cast<std::size_t>(g.classes.classCount()));
    i = 0;
    const double continuous = bench::medianMicroseconds(
        [&] {
            const Tap& tap = *gTests[i++ % gTests.size()];
            g.classifier.perceptScores(tap, gl.data());
            sink += perceiveContinuous(g.classes, gl.data(), tap.sampleCount()).position;
        },
        5000);
    bench::report("continuous percept of one tap (648 classes)", continuous, "us", 8.0);
    std::vector<std::vector<Vec2>> paths;
    for (const TrialRun& t : g.trials)
        if (t.result.completed()) paths.push_back(t.result.path());
    i = 0;
    const double recognition = bench::medianMicroseconds(
        [&] { sink += recognisePose(paths[i++ % paths.size()], g.poseTemplates).valid; }, 200);
    bench::report("recognise a path at any pose (12 shapes)", recognition / 1000.0, "ms", 1.0);
    bench::reportClock("this machine's clock, at the end");
    return sink == -1;
}
