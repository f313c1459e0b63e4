#include "core/run/Sweeps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include "core/classify/BeliefCalibration.h"
#include "core/classify/SequentialPerception.h"
#include "core/run/ExperimentRun.h"
#include "core/run/PerceptionSweep.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {
namespace {

/// One of each object the experiment follows.
std::vector<const TrialSpec*> objectsFollowed(const RunResult& r) {
    std::vector<const TrialSpec*> objects;
    for (const auto& t : r.spec.trials) {
        bool seen = false;
        for (const auto* o : objects) seen = seen || o->label == t.label;
        if (!seen) objects.push_back(&t);
    }
    return objects;
}

/// One trial following `object` with the setting of `row` on a rig of its own, whose random
/// streams are named by `tag`.
TrialResult followOnce(const RunResult& r, const RunOptions& options,
                       const std::shared_ptr<const FingertipContactModel>& model,
                       const TrialSpec& object, const FollowingSweepRow& row,
                       const std::string& tag) {
    SceneSpec scene = r.spec.scene;
    scene.object = object.object;
    scene.seed = RandomStream::derived(r.spec.scene.seed, tag).next() >> 1;
    const auto simulated = simulatedRigsOf(options).build(scene, model);
    Rig rig = simulated->rig();
    FollowingSettings settings = r.spec.following;
    settings.followStep_mm = row.followStep_mm;
    settings.repositionStep_mm = row.repositionStep_mm;
    settings.beliefThreshold = row.beliefThreshold;
    const Polygon outline = simulated->object();
    const TrialSetup setup = trialSetupFor(r, row.mode, settings, outline, object.start);
    return runTrial(rig, r.classifier, r.classes, outline, setup,
                    [&](const FollowedTap&) { return !options.stopRequested(); });
}

std::vector<FollowingSweepRow> followingSweep(const RunResult& r, const RunOptions& options) {
    const SweepSpec& sw = r.spec.sweeps;
    const std::vector<const TrialSpec*> objects = objectsFollowed(r);
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
                            if (options.stopRequested()) return rows;
                            const TrialResult t =
                                followOnce(r, options, model, *object, row,
                                           "sweep:following:" + std::to_string(setting) + ":" +
                                               object->label + ":" + std::to_string(k));
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
            if (options.stopRequested()) return rows;
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
                row.angleError_deg += angleDifferenceDeg(r.classes.orientationDegOf(decided[i]),
                                                         r.classes.orientationDegOf(testLabels[i]));
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

BanditResult banditSweep(const RunResult& r, const RunOptions& options,
                         const std::vector<FollowingSweepRow>& sweep) {
    const SweepSpec& sw = r.spec.sweeps;
    BanditResult b;
    b.completionWorth_s = sw.completionWorth_s;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
        const FollowingSweepRow& row = sweep[i];
        if (row.mode != FollowingMode::Active) continue;
        b.arms.push_back({int(i), row.followStep_mm, row.repositionStep_mm, row.beliefThreshold});
        b.sweepRobotTime_s += row.meanRobotTime_s * row.trials;
    }
    const std::vector<const TrialSpec*> objects = objectsFollowed(r);
    if (b.arms.empty() || objects.empty()) return b;
    const int A = static_cast<int>(b.arms.size());
    const int rounds = sw.banditRounds > 0 ? sw.banditRounds : 4 * A;
    auto model = std::make_shared<const FingertipContactModel>(r.spec.scene.fingertip);
    double highest = -std::numeric_limits<double>::infinity(), lowest = -highest;
    for (int n = 0; n < rounds; ++n) {
        if (options.stopRequested()) return b;
        // UCB1: every arm once, then the highest mean plus its exploration bonus, scaled by the
        // range of the rewards seen so far (at least 1, the worth of a completion).
        int arm = n < A ? n : 0;
        if (n >= A) {
            double bestIndex = -std::numeric_limits<double>::infinity();
            const double range = std::max(1.0, highest - lowest);
            for (int a = 0; a < A; ++a) {
                const BanditArm& x = b.arms[std::size_t(a)];
                const double index =
                    x.meanReward() + range * std::sqrt(2.0 * std::log(double(n)) / x.pulls);
                if (index > bestIndex) bestIndex = index, arm = a;
            }
        }
        BanditArm& x = b.arms[std::size_t(arm)];
        // Each arm follows the experiment's objects in turn, so that no arm sees only the easy
        // ones.
        const TrialSpec& object = *objects[std::size_t(x.pulls) % objects.size()];
        const TrialResult t = followOnce(r, options, model, object, sweep[std::size_t(x.sweepRow)],
                                         "sweep:bandit:" + std::to_string(n));
        ++x.pulls;
        x.completed += t.completed();
        x.robotTime_s += t.robotTime_s;
        const double reward = banditReward(t.completed(), t.robotTime_s, sw.completionWorth_s);
        x.rewardSum += reward;
        highest = std::max(highest, reward);
        lowest = std::min(lowest, reward);
        b.robotTime_s += t.robotTime_s;
        ++b.rounds;
    }
    b.ran = true;
    auto sweepReward = [&](const BanditArm& a) {  // the mean reward over (b)'s trials
        const FollowingSweepRow& row = sweep[std::size_t(a.sweepRow)];
        return double(row.completed) / std::max(1, row.trials) -
               row.meanRobotTime_s / sw.completionWorth_s;
    };
    for (int a = 0; a < A; ++a) {
        const BanditArm& x = b.arms[std::size_t(a)];
        if (b.chosen < 0 || x.pulls > b.arms[std::size_t(b.chosen)].pulls ||
            (x.pulls == b.arms[std::size_t(b.chosen)].pulls &&
             x.meanReward() > b.arms[std::size_t(b.chosen)].meanReward()))
            b.chosen = a;
        if (b.sweepBest < 0 || sweepReward(x) > sweepReward(b.arms[std::size_t(b.sweepBest)]))
            b.sweepBest = a;
    }
    b.chosenSweepReward = sweepReward(b.arms[std::size_t(b.chosen)]);
    b.bestSweepReward = sweepReward(b.arms[std::size_t(b.sweepBest)]);
    return b;
}

RobustnessRow robustnessRow(const std::string& fault, const RunResult& run) {
    RobustnessRow row;
    row.fault = fault;
    row.failure = run.failure;
    for (const TrialRun& t : run.trials) {
        if (t.result.end == TrialEnd::DeviceError || t.result.mode != FollowingMode::Active)
            continue;  // a device error fails the run, not the trial
        ++row.activeTrials;
        if (!t.result.completed()) continue;
        ++row.activeCompleted;
        if (!t.recognised) continue;
        ++row.recognitionTrials;
        row.recognisedRaw += t.recognition.predicted == t.label;
        const PoseRecognition& pose = t.poseRecognition;
        row.recognisedAnyPose += pose.valid && pose.predicted == t.label;
    }
    row.angleError_deg = run.validation.angleError_deg;
    row.positionError_mm = run.validation.positionError_mm;
    return row;
}

/// The whole experiment again on the run's seed for each fault, the fault's effect added to the
/// scene (replacing one of the same name), with nothing written and no sweeps.
std::vector<RobustnessRow> robustnessSweep(const RunResult& r, const RunOptions& options) {
    std::vector<RobustnessRow> rows;
    for (const SweepSpec::Fault& fault : r.spec.sweeps.faults) {
        if (options.stopRequested()) break;
        ExperimentSpec spec = r.spec;
        spec.sweeps = {};
        auto& effects = spec.scene.effects;
        const auto same = std::find_if(effects.begin(), effects.end(), [&](const EffectSpec& e) {
            return e.name == fault.effect.name;
        });
        if (same != effects.end())
            *same = fault.effect;
        else
            effects.push_back(fault.effect);
        RunOptions once;
        once.simulated = options.simulated;
        once.seed = r.spec.scene.seed;
        once.reportsBeliefCalibration = false;  // a row is the trials' outcomes
        // Cancelling the run cancels this one (its observer hears only that question).
        struct Relay : RunObserver {
            const RunOptions* outer = nullptr;
            bool stopRequested() const override { return outer->stopRequested(); }
        } relay;
        relay.outer = &options;
        once.observer = &relay;
        rows.push_back(robustnessRow(fault.name, runExperimentOrFailure(spec, once)));
    }
    return rows;
}

}  // namespace

SweepSpec standardSweeps() {
    SweepSpec s;
    s.beliefThresholds = {0.5, 0.8, 0.9, 0.95, 0.99, 0.995, 0.999};
    s.tapsPerClass = 20;
    s.maxTapsPerDecision = 20;
    s.followSteps_mm = {1, 2, 3, 4};
    s.repositionSteps_mm = {0.5, 1, 2};
    s.followingBeliefThresholds = {0, 0.9, 0.99};
    s.modes = {FollowingMode::Active, FollowingMode::Passive};
    s.followingRepeats = 3;
    s.bins = {10, 25, 50, 100, 200};
    s.samplesPerTap = {5, 10, 25, 50};
    s.bandit = true;
    s.banditRounds = 144;
    s.completionWorth_s = 2000.0;
    return s;
}

SweepResults runSweeps(const RunResult& trained, const RunOptions& options, bool onTapsOnly) {
    SweepResults s;
    const SweepSpec& sw = trained.spec.sweeps;
    if (!trained.classifier.trained()) return s;
    if (!sw.bins.empty()) s.compute = computeSweep(trained, options);
    if (onTapsOnly) return s;
    if (!sw.beliefThresholds.empty())
        s.perception =
            perceptionSweep(trained, options, s.perceptionCalibration, s.perceptionSingleTap);
    if (!sw.followSteps_mm.empty()) s.following = followingSweep(trained, options);
    if (sw.bandit && !s.following.empty()) s.bandit = banditSweep(trained, options, s.following);
    if (!sw.faults.empty()) {
        s.robustnessBase = robustnessRow("none", trained);
        s.robustness = robustnessSweep(trained, options);
    }
    return s;
}

}  // namespace activetouch
