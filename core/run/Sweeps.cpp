#include "core/run/Sweeps.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "core/run/ExperimentRun.h"
#include "core/classify/SequentialPerception.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {
namespace {

bool cancelled(const RunOptions& o) {
    return o.observer && o.observer->stopRequested();
}

double angleError(const ClassSet& cs, int perceived, int truth) {
    return angleDifferenceDeg(cs.orientationDegOf(perceived), cs.orientationDegOf(truth));
}

std::vector<PerceptionSweepRow> perceptionSweep(const RunResult& r, const RunOptions& options) {
    const SweepSpec& sw = r.spec.sweeps;
    // Fresh repeated taps of every class, as the training protocol takes them.
    auto model = std::make_shared<const FingertipContactModel>(r.spec.scene.fingertip);
    SceneSpec scene = r.spec.scene;
    scene.seed = RandomStream::derived(r.spec.scene.seed, "sweep:perception").next() >> 1;
    const auto simulated = simulatedRigsOf(options).build(scene, model);
    Rig rig = simulated->rig();
    TrainingProtocolSettings protocol = r.spec.training;
    protocol.dataSets = std::max(2, sw.tapsPerClass);
    protocol.trainingSets = {};
    const auto taps = collectTrainingTaps(rig, simulated->object(), r.classes, protocol,
                                          RandomStream::derived(scene.seed, "sweep:placement"),
                                          [&](const CollectedTap&) { return !cancelled(options); });
    std::map<int, std::vector<const CollectedTap*>> byClass;
    for (const auto& t : taps) byClass[t.cls].push_back(&t);
    // Log-likelihoods once per tap.
    std::map<const CollectedTap*, std::vector<double>> evidence;
    for (const auto& t : taps) {
        std::vector<double> ll(static_cast<std::size_t>(r.classes.classCount()));
        r.classifier.logLikelihoods(t.record.tap, ll.data());
        evidence[&t] = std::move(ll);
    }
    std::vector<PerceptionSweepRow> rows;
    for (double threshold : sw.beliefThresholds) {
        PerceptionSweepRow row{threshold, 0, 0, 0, 0};
        int decisions = 0;
        for (const auto& [cls, list] : byClass) {
            // Each starting tap begins one sequence through the class's repeats, in turn.
            for (std::size_t start = 0; start < list.size(); ++start) {
                SequentialBelief belief(r.classes);
                const CollectedTap* last = nullptr;
                for (std::size_t k = 0; k < list.size() && belief.taps() < sw.maxTapsPerDecision;
                     ++k) {
                    last = list[(start + k) % list.size()];
                    belief.update(evidence[last].data());
                    if (belief.decided(threshold)) break;
                }
                const int perceived = belief.best();
                row.meanTaps += belief.taps();
                row.angleError_deg += angleError(r.classes, perceived, cls);
                row.positionError_mm += std::abs(
                    r.classes.offsetOf(r.classes.positionOf(perceived)) - last->trueOffset_mm);
                row.correctFraction += perceived == cls;
                ++decisions;
            }
        }
        if (decisions == 0) break;
        row.meanTaps /= decisions;
        row.angleError_deg /= decisions;
        row.positionError_mm /= decisions;
        row.correctFraction /= decisions;
        rows.push_back(row);
    }
    return rows;
}

std::vector<FollowingSweepRow> followingSweep(const RunResult& r, const RunOptions& options) {
    const SweepSpec& sw = r.spec.sweeps;
    // One of each object the experiment follows.
    std::vector<const TrialSpec*> objects;
    for (const auto& t : r.spec.trials) {
        bool seen = false;
        for (const auto* o : objects) seen = seen || o->label == t.label;
        if (!seen) objects.push_back(&t);
    }
    auto model = std::make_shared<const FingertipContactModel>(r.spec.scene.fingertip);
    std::vector<FollowingSweepRow> rows;
    int setting = 0;
    for (FollowingMode mode : sw.modes) {
        for (double follow : sw.followSteps_mm) {
            for (double reposition : (mode == FollowingMode::Active ? sw.repositionSteps_mm
                                                                    : std::vector<double>{0.0})) {
                for (double threshold : sw.followingBeliefThresholds) {
                    FollowingSweepRow row{mode, follow, reposition, threshold};
                    row.paperSetting = follow == 2.0 &&
                                       (mode == FollowingMode::Passive || reposition == 1.0) &&
                                       threshold == 0.0;
                    double time = 0, taps = 0, distance = 0;
                    for (const TrialSpec* object : objects) {
                        for (int k = 0; k < sw.followingRepeats; ++k) {
                            if (cancelled(options)) return rows;
                            SceneSpec scene = r.spec.scene;
                            scene.object = object->object;
                            scene.seed = RandomStream::derived(
                                             r.spec.scene.seed,
                                             "sweep:following:" + std::to_string(setting) + ":" +
                                                 object->label + ":" + std::to_string(k))
                                             .next() >>
                                         1;
                            const auto simulated = simulatedRigsOf(options).build(scene, model);
                            Rig rig = simulated->rig();
                            FollowingSettings settings = r.spec.following;
                            settings.followStep_mm = follow;
                            settings.repositionStep_mm = reposition;
                            settings.beliefThreshold = threshold;
                            const Polygon outline = simulated->object();
                            const TrialSetup setup =
                                trialSetupFor(r, mode, settings, outline, object->start);
                            const TrialResult t =
                                runTrial(rig, r.classifier, r.classes, outline, setup,
                                         [&](const FollowedTap&) { return !cancelled(options); });
                            ++row.trials;
                            row.completed += t.completed();
                            time += t.robotTime_s;
                            taps += static_cast<double>(t.taps.size());
                            distance += t.meanContourDistance_mm;
                        }
                    }
                    ++setting;
                    row.meanRobotTime_s = time / row.trials;
                    row.meanTaps = taps / row.trials;
                    row.meanContourDistance_mm = distance / row.trials;
                    row.robotTimePerCompletion_s = row.completed > 0
                                                       ? time / row.completed
                                                       : std::numeric_limits<double>::infinity();
                    rows.push_back(row);
                }
            }
        }
    }
    return rows;
}

Tap subsampled(const Tap& tap, int samples) {
    // Evenly spaced samples across the tap window: a lower sampling rate over the same tap.
    Tap out(samples, tap.taxels);
    const int T = tap.sampleCount();
    for (int s = 0; s < samples; ++s) {
        const int from =
            samples == 1 ? T / 2 : static_cast<int>(std::lround(s * (T - 1.0) / (samples - 1)));
        for (int k = 0; k < tap.taxels; ++k) out.at(s, k) = tap.at(from, k);
    }
    return out;
}

std::vector<ComputeSweepRow> computeSweep(const RunResult& r, const RunOptions& options) {
    const SweepSpec& sw = r.spec.sweeps;
    std::vector<ComputeSweepRow> rows;
    for (int samples : sw.samplesPerTap) {
        std::vector<Tap> train, test;
        std::vector<int> trainLabels, testLabels;
        std::vector<double> testOffsets;
        for (const auto& t : r.taps) {
            if (r.spec.training.isTrainingSet(t.dataSet)) {
                train.push_back(subsampled(t.record.tap, samples));
                trainLabels.push_back(t.cls);
            } else {
                test.push_back(subsampled(t.record.tap, samples));
                testLabels.push_back(t.cls);
                testOffsets.push_back(t.trueOffset_mm);
            }
        }
        std::vector<LabelledTap> labelled;
        for (std::size_t i = 0; i < train.size(); ++i)
            labelled.push_back({&train[i], trainLabels[i]});
        for (int bins : sw.bins) {
            if (cancelled(options)) return rows;
            ClassifierSettings settings = r.spec.classifier;
            settings.bins = bins;
            const HistogramClassifier c =
                HistogramClassifier::train(labelled, r.classes.classCount(), settings);
            ComputeSweepRow row{bins, samples, 0,
                                0,    0,       bins == 100 && samples == r.spec.scene.tap.samples};
            std::vector<int> decided(test.size());
            // Time the decisions over enough repetitions to measure; report per decision.
            const int repeats =
                std::max(1, static_cast<int>(20000 / std::max<std::size_t>(1, test.size())));
            const auto t0 = std::chrono::steady_clock::now();
            for (int rep = 0; rep < repeats; ++rep)
                for (std::size_t i = 0; i < test.size(); ++i) decided[i] = c.classify(test[i]);
            const auto t1 = std::chrono::steady_clock::now();
            row.microsecondsPerDecision =
                std::chrono::duration<double, std::micro>(t1 - t0).count() /
                (repeats * static_cast<double>(test.size()));
            for (std::size_t i = 0; i < test.size(); ++i) {
                row.angleError_deg += angleError(r.classes, decided[i], testLabels[i]);
                row.positionError_mm +=
                    std::abs(r.classes.offsetOf(r.classes.positionOf(decided[i])) - testOffsets[i]);
            }
            row.angleError_deg /= static_cast<double>(test.size());
            row.positionError_mm /= static_cast<double>(test.size());
            rows.push_back(row);
        }
    }
    return rows;
}

}  // namespace

SweepResults runSweeps(const RunResult& trained, const RunOptions& options, bool onTapsOnly) {
    SweepResults s;
    const SweepSpec& sw = trained.spec.sweeps;
    if (!trained.classifier.trained()) return s;
    if (!sw.bins.empty()) s.compute = computeSweep(trained, options);
    if (onTapsOnly) return s;
    if (!sw.beliefThresholds.empty()) s.perception = perceptionSweep(trained, options);
    if (!sw.followSteps_mm.empty()) s.following = followingSweep(trained, options);
    return s;
}

}  // namespace activetouch
