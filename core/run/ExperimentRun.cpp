#include "core/run/ExperimentRun.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "core/common/NumberText.h"
#include "core/control/ControllerRange.h"
#include "core/experiment/RunPlan.h"
#include "core/geometry/ShapeLibrary.h"
#include "core/recognition/ShapeRecognition.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "core/run/OutputFiles.h"
#include "core/run/RecordedRuns.h"
#include "core/run/ReplayRig.h"
#include "core/run/RunFolder.h"
#include "core/run/Sweeps.h"
#include "core/run/TrialRecognition.h"
#include "core/stats/Intervals.h"
#include "core/validation/ClassRegions.h"

namespace activetouch {
namespace fs = std::filesystem;

namespace {

bool sameOutline(const Polygon& a, const Polygon& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (distance(a.vertex(i), b.vertex(i)) > 1e-6) return false;
    return true;
}

}  // namespace

void checkRunnableOn(const ExperimentSpec& spec, const ConnectedRig& connected) {
    checkRunnableOn(spec, connected.object);
}

void checkRunnableOn(const ExperimentSpec& spec, const ObjectSpec& object) {
    const Polygon mounted = object.outline();
    const std::string fix =
        "; mount that object and describe it in the scene, or run this on the simulated rig "
        "(disconnect the devices)";
    if (!sameOutline(spec.scene.object.outline(), mounted))
        throw InputError(spec.name, "/scene/object",
                         "the scene's " + spec.scene.object.shape +
                             " is not the object on the connected rig (" + object.shape + ")" +
                             fix);
    for (const TrialSpec& t : spec.trials)
        if (!sameOutline(t.object.outline(), mounted))
            throw InputError(spec.name, t.place,
                             "trial '" + t.label + "' is on a " + t.object.shape +
                                 " at another place than the object on the connected rig (" +
                                 object.shape + ")" + fix);
    if (spec.sweeps.any())
        throw InputError(spec.name, "/sweeps",
                         "sweeps run on simulated rigs only; run this experiment with the devices "
                         "disconnected, or remove its sweeps");
}

TrialSetup trialSetupFor(const RunResult& trained, FollowingMode mode,
                         const FollowingSettings& settings, const Polygon& outline,
                         const std::optional<Vec2>& start) {
    TrialSetup setup;
    setup.mode = mode;
    setup.settings = settings;
    setup.valid = trained.validOffsets;
    setup.noiseFloor = trained.noiseFloor_counts;
    setup.contactRadius_mm = trained.contactRadius_mm;
    setup.start = start ? *start : lowerEdgeStart(outline, trained.validOffsets);
    if (trained.beliefCalibration.measured && settings.calibratedBelief)
        setup.beliefScaling = trained.beliefCalibration.sequential;
    if (settings.percept == PerceptKind::Continuous) {
        // Placed on an edge, the tip starts knowing which way that edge faces, as a paper trial
        // knows it starts on the lower edge; a continuous percept takes the edge's own angle
        // rather than the nearest trained orientation.
        const Vec2 n = outline.outwardNormal(outline.nearestOutlinePoint(setup.start).edge);
        setup.startEdgeDeg = degreesOf(n);
    }
    return setup;
}

const SimulatedRigs& simulatedRigsOf(const RunOptions& options) {
    if (!options.simulated)
        throw std::logic_error("a run on the simulated rig was given no simulated rigs");
    return *options.simulated;
}

int plannedTapEstimate(const ExperimentSpec& spec) {
    // Training taps are known; a trial takes about a perimeter's worth of follow steps plus the
    // repositioning around corners (RunPlan). A plan beyond an int's range is refused before any
    // run unless asked for; a progress count saturates there.
    const RunPlan plan = planOf(spec);
    return static_cast<int>(
        std::min(plan.trainingTaps + plan.trialTaps, double(std::numeric_limits<int>::max())));
}

namespace {

/// Adds to a replayed trial that left its recording what the recording and the replay perceived
/// and decided at the tap where they parted.
void noteWhereReplayLeft(const RecordedTrial& recorded, TrialResult& replayed) {
    const std::size_t k = replayed.taps.size();
    if (k == 0 || k >= recorded.taps.size()) return;  // parted at the start, or at the end
    const RecordedDecision& was = recorded.decisions[k - 1];
    const FollowedTap& now = replayed.taps[k - 1];
    replayed.detail += "; they parted at tap " + std::to_string(k - 1) + ": the recording read " +
                       was.shapeClass + ", position " + std::to_string(was.position) + " -> " +
                       was.rule + ", the replay " + now.percept.shapeClass() + ", position " +
                       std::to_string(now.percept.position) + " -> " +
                       ruleFor(now.decision.rule).name;
}

/// What a trial does with each tap: appends it to the recording, tells the observer, counts the
/// run's progress; false once the observer asks to stop.
std::function<bool(const FollowedTap&)> tapListener(FollowingRecording* recording,
                                                    const TrialRun& run, FollowingMode mode,
                                                    const RunOptions& options,
                                                    RunProgress& progress, int& tapIndex) {
    return [recording, &run, mode, &options, &progress, &tapIndex](const FollowedTap& tap) {
        if (recording) recording->append(run.label, mode, run.trial, tapIndex, tap);
        if (options.observer)
            options.observer->tapTaken(
                tap.record,
                std::string(modeName(mode)) + " " + run.label + " trial " +
                    std::to_string(run.trial) + ": " + tap.percept.shapeClass() + ", position " +
                    std::to_string(tap.percept.position) + " -> " + ruleFor(tap.decision.rule).name,
                RunObserver::Stage::Following);
        ++tapIndex;
        ++progress.tapsDone;
        if (options.observer) options.observer->progressed(progress);
        return !(options.observer && options.observer->stopRequested());
    };
}

/// Runs the experiment's trials, each on the simulated rig, the connected one, or (`replayed`
/// not empty) the recorded trial at its index.
void runTrials(RunResult& result, std::shared_ptr<const FingertipContactModel> model,
               const RunOptions& options, RunProgress& progress,
               const std::vector<const RecordedTrial*>& replayed = {}) {
    const ExperimentSpec& spec = result.spec;
    result.contactRadius_mm =
        model->edgeContactRadius(spec.scene.tap.contactThreshold, spec.scene.strokeLimitDepth());
    if (spec.trials.empty()) return;
    std::unique_ptr<FollowingRecording> recording;
    if (!options.outDir.empty())
        recording = std::make_unique<FollowingRecording>(
            (fs::path(options.outDir) / "data" / "following_taps.csv").string(),
            model->taxelCount());
    std::map<std::string, int> counters;  // trials so far per (label, mode)
    int trialIndex = 0;
    for (const TrialSpec& ts : spec.trials) {
        for (int repeat = 0; repeat < ts.repeats; ++repeat, ++trialIndex) {
            // On the simulated rig each trial gets its own world on the trial's object, with its
            // own noise; a connected rig has the one object mounted; a replay serves the
            // recorded trial.
            std::unique_ptr<SceneRig> simulated;
            std::optional<ReplayRig> replay;
            if (!replayed.empty()) {
                replay.emplace(*replayed[static_cast<std::size_t>(trialIndex)],
                               options.recordingName);
            }
            ObjectSpec object = ts.object;
            if (object.rotationDrawn)
                object.rotationDeg =
                    RandomStream::derived(spec.scene.seed,
                                          "trial rotation:" + std::to_string(trialIndex))
                        .uniform(0.0, 360.0);
            if (!replay && !options.connected) {
                SceneSpec scene = spec.scene;
                scene.object = object;
                scene.seed =
                    RandomStream::derived(spec.scene.seed, "trial:" + std::to_string(trialIndex))
                        .next() >>
                    1;
                simulated = simulatedRigsOf(options).build(scene, model);
            }
            Rig rig = replay              ? replay->rig()
                      : options.connected ? options.connected->rig
                                          : simulated->rig();
            TrialRun run;
            if (replay)
                run.recordedTaps =
                    static_cast<int>(replayed[static_cast<std::size_t>(trialIndex)]->taps.size());
            run.label = ts.label;
            run.trial = ++counters[ts.label + "/" + modeName(ts.mode)];
            run.outline = simulated ? simulated->object() : object.outline();
            run.rotationDeg = object.rotationDeg;
            run.objectOffset = object.offset;
            const TrialSetup setup =
                trialSetupFor(result, ts.mode, spec.following, run.outline, ts.start);
            run.start = setup.start;
            progress.step = std::string(modeName(ts.mode)) + " following, " + ts.label + " trial " +
                            std::to_string(run.trial);
            int tapIndex = 0;
            run.result =
                runTrial(rig, result.classifier, result.classes, run.outline, setup,
                         tapListener(recording.get(), run, ts.mode, options, progress, tapIndex));
            if (replay && run.result.end == TrialEnd::LeftRecording)
                noteWhereReplayLeft(*replayed[static_cast<std::size_t>(trialIndex)], run.result);
            result.robotTime_s += run.result.robotTime_s;
            if (simulated) result.tapsSimulated += simulated->tapsSimulated();
            result.trials.push_back(std::move(run));
            if (result.trials.back().result.end == TrialEnd::DeviceError) {
                result.failure = result.trials.back().result.detail;
                return;
            }
            if (result.trials.back().result.end == TrialEnd::Cancelled) {
                result.cancelled = true;
                return;
            }
        }
    }
    summarisePathAngles(result);
    if (spec.recognition.enabled) recogniseTrialPaths(result);
}

/// Trains the classifier on the training sets of `result.taps` and validates it on the others:
/// the measured noise floor and the class regions from it, the offline validation, the valid
/// range and trusted span the controller follows with, the belief's calibration on the held-out
/// taps where `calibrate`, and (if the experiment asks) the classifier trained again on every set.
void trainAndValidate(RunResult& result, const std::vector<IdealClassContact>& ideal,
                      bool calibrate) {
    const ExperimentSpec& spec = result.spec;
    // The taps that touched nothing give the floor a tap must rise above to count as contact;
    // classes whose ideal tap stays below it are air.
    std::vector<ClassTap> all;
    for (const auto& t : result.taps) all.push_back({t.cls, &t.record.tap});
    result.measuredNoiseFloor = measureNoiseFloor(ideal, all);
    if (result.measuredNoiseFloor)
        result.noiseFloor_counts =
            std::max(result.noiseFloor_counts, result.measuredNoiseFloor->counts);
    result.classes.regions = classRegions(ideal, result.noiseFloor_counts);

    std::vector<LabelledTap> training;
    std::vector<const CollectedTap*> tests;
    for (const auto& t : result.taps) {
        if (spec.training.isTrainingSet(t.dataSet))
            training.push_back({&t.record.tap, t.cls});
        else
            tests.push_back(&t);
    }
    result.classifier =
        HistogramClassifier::train(training, result.classes.classCount(), spec.classifier);
    result.validation = validateOffline(
        result.classifier, result.classes, tests, spec.validRangeWidth,
        spec.following.percept == PerceptKind::Continuous ? spec.following.perceptTemperature
                                                          : -1.0);
    if (calibrate) {
        std::vector<const Tap*> heldOut;
        std::vector<int> truth;
        for (const CollectedTap* t : tests) {
            heldOut.push_back(&t->record.tap);
            truth.push_back(t->cls);
        }
        result.beliefCalibration = calibrateBelief(result.classifier, heldOut, truth);
    }
    const ControllerRange range = controllerRange(result.classes, result.validation,
                                                  spec.following.orientationTrustMaxError_deg);
    result.validOffsets = range.offsets;
    result.trustedPositions = range.trustedPositions;
    if (spec.training.retrainOnAllSets) {
        // Validated on held-out sets, the classifier then learns from every tap taken: the trials
        // get the test taps too, at no extra tap.
        std::vector<LabelledTap> everySet;
        for (const auto& t : result.taps) everySet.push_back({&t.record.tap, t.cls});
        result.classifier =
            HistogramClassifier::train(everySet, result.classes.classCount(), spec.classifier);
        result.classifierRetrainedOnTaps = static_cast<int>(everySet.size());
    }
}

/// Where the run's taps come from, said in the result.
void noteRig(RunResult& result, const RunOptions& options, const SceneRig* simulated) {
    if (simulated)
        result.activeEffects = simulated->activeEffects();
    else if (options.recordedTaps)
        result.rig = (options.recordedTrials ? "replay of " : "recording ") + options.recordingName;
    else
        result.rig = options.connected->description;
}

/// The training and test taps into result.taps, read from the recording or taken on the rig,
/// each written to `recording` and told to the observer as it comes; false when the run was
/// stopped before every planned tap.
bool takeTrainingTaps(RunResult& result, const RunOptions& options, SceneRig* simulated,
                      RunProgress& progress, TapCsvWriter* recording) {
    const ExperimentSpec& spec = result.spec;
    auto onTap = [&](const CollectedTap& tap) {
        if (recording) recording->append(tap, result.classes);
        if (options.observer)
            options.observer->tapTaken(
                tap.record,
                "training set " + std::to_string(tap.dataSet) + ": " +
                    ClassSet::orientationName(result.classes.orientationDegOf(tap.cls)) +
                    " edge, position " + std::to_string(result.classes.positionOf(tap.cls)),
                RunObserver::Stage::Training);
        ++progress.tapsDone;
        if (options.observer) options.observer->progressed(progress);
        return !options.stopRequested();
    };
    if (const auto* recorded = options.recordedTaps) {
        for (const CollectedTap& tap : *recorded) {
            result.taps.push_back(tap);
            if (!onTap(tap)) break;
        }
        if (!result.taps.empty())
            result.robotTime_s =
                result.taps.back().record.startTime_s - result.taps.front().record.startTime_s;
        return result.taps.size() >= recorded->size();
    }
    Rig rig = options.connected ? options.connected->rig : simulated->rig();
    const double robotStart_s = rig.clock.now_s();
    result.taps = collectTrainingTaps(
        rig, simulated ? simulated->object() : spec.scene.object.outline(), result.classes,
        spec.training, RandomStream::derived(spec.scene.seed, "protocol:placement"), onTap);
    result.robotTime_s = rig.clock.now_s() - robotStart_s;
    if (simulated) result.tapsSimulated = simulated->tapsSimulated();
    return static_cast<std::int64_t>(result.taps.size()) >= spec.plannedTaps();
}

/// After training: the trials and the sweeps. A recording is analysed offline: its trials, if
/// any, replay on the recorded taps, and of the sweeps only the one on the recorded taps
/// themselves runs.
void runAfterTraining(RunResult& result, const std::shared_ptr<const FingertipContactModel>& model,
                      const RunOptions& options, RunProgress& progress,
                      const std::vector<const RecordedTrial*>& replayed) {
    const ExperimentSpec& spec = result.spec;
    const bool recorded = options.recordedTaps != nullptr;
    if (!recorded)
        runTrials(result, model, options, progress);
    else if (!replayed.empty() && !result.cancelled)
        runTrials(result, model, options, progress, replayed);
    const bool sweeps = recorded ? !spec.sweeps.bins.empty() : spec.sweeps.any();
    if (!sweeps || result.cancelled || !result.failure.empty()) return;
    progress.step = recorded ? "compute sweep on the recorded taps" : "accuracy-versus-time sweeps";
    if (options.observer) options.observer->progressed(progress);
    result.sweeps = runSweeps(result, options, recorded);
}

}  // namespace

RunResult runExperiment(const ExperimentSpec& specIn, const RunOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    RunResult result;
    result.spec = specIn;
    if (options.seed) result.spec.scene.seed = *options.seed;
    const ExperimentSpec& spec = result.spec;

    auto model = FingertipContactModel::shared(spec.scene.fingertip);
    const std::vector<CollectedTap>* recorded = options.recordedTaps;
    if (recorded) checkRecordingCovers(spec, *recorded, model->taxelCount(), options.recordingName);
    // A replay's trials: each of the experiment's trials has its recording, of one tap shape.
    std::vector<const RecordedTrial*> replayed;
    if (recorded && options.recordedTrials) {
        replayed = replayedTrialsFor(spec, *options.recordedTrials, options.recordingName);
        checkReplayedTapsMatch(replayed, recorded->front().record.tap, options.recordingName);
    }
    if (options.connected) checkRunnableOn(spec, *options.connected);
    std::unique_ptr<SceneRig> simulated;
    if (!options.connected && !recorded)
        simulated = simulatedRigsOf(options).build(spec.scene, model);
    noteRig(result, options, simulated.get());
    result.classes = spec.classes;
    const auto ideal =
        idealClassContacts(*model, spec.classes, spec.scene.tap, spec.scene.strokeLimitDepth());
    result.noiseFloor_counts = spec.scene.tap.noiseFloor;
    result.classes.regions = classRegions(ideal, result.noiseFloor_counts);

    std::unique_ptr<TapCsvWriter> recording;
    if (!options.outDir.empty()) {
        if (options.beforeWriting) options.beforeWriting();
        ensureOutputDirectory((fs::path(options.outDir) / "data").string());
        recording = std::make_unique<TapCsvWriter>(
            (fs::path(options.outDir) / "data" / "taps.csv").string(), model->taxelCount());
    }

    RunProgress progress;
    progress.step = recorded ? "recorded training and test taps" : "training and test taps";
    progress.tapsPlanned = recorded ? static_cast<int>(recorded->size()) : plannedTapEstimate(spec);
    for (const RecordedTrial* t : replayed)
        progress.tapsPlanned += static_cast<int>(t->taps.size());
    if (takeTrainingTaps(result, options, simulated.get(), progress, recording.get())) {
        // Measured where it is read: the caller reports it, or the trials or sweeps use it.
        trainAndValidate(result, ideal,
                         options.reportsBeliefCalibration ||
                             spec.following.readsBeliefCalibration() || spec.sweeps.any());
        runAfterTraining(result, model, options, progress, replayed);
    } else {
        result.cancelled = true;
    }
    result.runWall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

RunResult runExperimentOrFailure(const ExperimentSpec& spec, const RunOptions& options) {
    try {
        return runExperiment(spec, options);
    } catch (const RigError& e) {
        RunResult failed;
        failed.spec = spec;
        if (options.seed) failed.spec.scene.seed = *options.seed;
        failed.failure = std::string("during the training taps: ") + e.what();
        return failed;
    }
}

std::string followingClassifierNote(const RunResult& r) {
    if (r.classifierRetrainedOnTaps == 0) return {};
    return "following classifier: trained again after validation on all " +
           std::to_string(r.spec.training.dataSets) + " data sets (" +
           std::to_string(r.classifierRetrainedOnTaps) +
           " taps, test sets included); the validation above is the training sets' alone";
}

std::vector<std::string> trainingSettingsChanged(const RunResult& trained,
                                                 const ExperimentSpec& spec) {
    std::vector<std::string> changed;
    auto list = [](const auto& values) {
        std::string text;
        for (const auto& v : values) text += (text.empty() ? "" : ", ") + numberText(double(v));
        return text;
    };
    auto compare = [&](const char* what, const std::string& then, const std::string& now) {
        if (then != now) changed.push_back(std::string(what) + ": " + then + " -> " + now);
    };
    const ExperimentSpec& t = trained.spec;
    compare("edge orientations (deg)", list(t.classes.orientationsDeg),
            list(spec.classes.orientationsDeg));
    compare("positions", numberText(t.classes.positions), numberText(spec.classes.positions));
    compare("position step (mm)", numberText(t.classes.positionStep_mm),
            numberText(spec.classes.positionStep_mm));
    compare("histogram bins", numberText(t.classifier.bins), numberText(spec.classifier.bins));
    compare("smoothing", numberText(t.classifier.smoothing), numberText(spec.classifier.smoothing));
    compare("kernel width (bins)", numberText(t.classifier.kernelSigma_bins),
            numberText(spec.classifier.kernelSigma_bins));
    compare("data sets", numberText(t.training.dataSets), numberText(spec.training.dataSets));
    compare("training sets", list(t.training.trainingSets), list(spec.training.trainingSets));
    compare("taps per class", numberText(t.training.tapsPerClass),
            numberText(spec.training.tapsPerClass));
    compare("test sets off the grid (mm)", numberText(t.training.testOffset_mm),
            numberText(spec.training.testOffset_mm));
    compare("placement jitter (mm)", numberText(t.training.placementJitter_mm),
            numberText(spec.training.placementJitter_mm));
    compare("trained on every set", t.training.retrainOnAllSets ? "yes" : "no",
            spec.training.retrainOnAllSets ? "yes" : "no");
    compare("valid range (positions)", numberText(t.validRangeWidth),
            numberText(spec.validRangeWidth));
    return changed;
}

RunResult runFollowing(const RunResult& trained, const ExperimentSpec& specIn,
                       const RunOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    RunResult result = trained;
    result.spec = specIn;
    if (options.seed) result.spec.scene.seed = *options.seed;
    result.spec.training = trained.spec.training;
    result.spec.classifier = trained.spec.classifier;
    result.spec.classes = trained.spec.classes;
    result.taps.clear();
    result.trials.clear();
    result.templates.clear();
    result.cancelled = false;
    result.failure.clear();
    result.robotTime_s = 0.0;
    result.tapsSimulated = 0;
    result.rig = options.connected ? options.connected->description : "simulated";
    if (options.connected) checkRunnableOn(result.spec, *options.connected);
    if (!options.outDir.empty())
        ensureOutputDirectory((fs::path(options.outDir) / "data").string());
    auto model = FingertipContactModel::shared(result.spec.scene.fingertip);
    RunProgress progress;
    progress.tapsPlanned =
        static_cast<int>(plannedTapEstimate(result.spec) - result.spec.plannedTaps());
    runTrials(result, model, options, progress);
    result.runWall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

}  // namespace activetouch
