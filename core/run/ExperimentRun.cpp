#include "core/run/ExperimentRun.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "core/run/OutputFiles.h"
#include "core/run/RunFolder.h"
#include "core/common/NumberText.h"
#include "core/control/ControllerRange.h"
#include "core/experiment/RunPlan.h"
#include "core/geometry/ShapeLibrary.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "core/recognition/ShapeRecognition.h"
#include "core/validation/ClassRegions.h"
#include "core/run/ReplayRig.h"

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
    setup.start = start ? *start : lowerEdgeStart(outline, trained.validOffsets);
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

RecordedRun readRecordedRun(const std::string& runDir, const ClassSet& classes) {
    std::error_code ec;  // a path the system cannot look up is not a run's folder
    if (!fs::is_directory(runDir, ec))
        throw InputError(runDir, "",
                         "not a folder; give the folder a run wrote (it holds data/taps.csv and "
                         "data/following_taps.csv)");
    const fs::path data = fs::path(runDir) / "data";
    const std::string following = (data / "following_taps.csv").string(),
                      taps = (data / "taps.csv").string();
    if (!fs::exists(following, ec))
        throw InputError(following, "",
                         "the run recorded no contour following, so there is nothing to replay; "
                         "re-analyse its training taps instead (analyse)");
    if (!fs::exists(taps, ec))
        throw InputError(taps, "",
                         "no training taps beside the following recording: this run followed "
                         "with a classifier trained in an earlier run; copy that run's "
                         "data/taps.csv here to replay both");
    RecordedRun run;
    run.name = runDir;
    // Both files must be the one run's: a folder that mixes runs is refused, naming the file.
    const RecordingBounds bounds = checkedRecordingBounds(taps, &run.note);
    checkedRecordingBounds(following);
    run.taps = readTapCsv(taps, classes, &run.tapsCutOff, bounds);
    FollowingRecordingContents contents;
    run.trials = readFollowingRecording(following, &contents, bounds);
    run.followingTaps = contents.taps;
    run.trialsCutOff = contents.cutOff;
    return run;
}

std::vector<const RecordedTrial*> replayedTrialsFor(const ExperimentSpec& spec,
                                                    const std::vector<RecordedTrial>& recorded,
                                                    const std::string& name) {
    std::vector<const RecordedTrial*> replayed;
    std::map<std::string, int> counters;  // trials so far per (label, mode), as runTrials counts
    for (const TrialSpec& ts : spec.trials)
        for (int repeat = 0; repeat < ts.repeats; ++repeat) {
            const int trial = ++counters[ts.label + "/" + modeName(ts.mode)];
            // A trial named after its library shape also matches a recording that spelt the
            // name in another letter case ("c" for "C").
            const bool shapeLabel = ts.label == ts.object.shape;
            const auto it = std::find_if(recorded.begin(), recorded.end(), [&](const auto& r) {
                const bool sameLabel =
                    r.label == ts.label || (shapeLabel && libraryShapeName(r.label) == ts.label);
                return sameLabel && r.mode == ts.mode && r.trial == trial;
            });
            if (it == recorded.end())
                throw InputError(name, "",
                                 "the recording holds no " + std::string(modeName(ts.mode)) + " " +
                                     ts.label + " trial " + std::to_string(trial) +
                                     " (the experiment's " + ts.place +
                                     "); replay it with the experiment the run was made with, or "
                                     "leave that trial out of the experiment");
            replayed.push_back(&*it);
        }
    return replayed;
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

/// Runs the experiment's trials, each on the simulated rig, the connected one, or (`replayed`
/// not empty) the recorded trial at its index.
void runTrials(RunResult& result, std::shared_ptr<const FingertipContactModel> model,
               const RunOptions& options, RunProgress& progress,
               const std::vector<const RecordedTrial*>& replayed = {}) {
    const ExperimentSpec& spec = result.spec;
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
            } else if (!options.connected) {
                SceneSpec scene = spec.scene;
                scene.object = ts.object;
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
            run.outline = simulated ? simulated->object() : ts.object.outline();
            const TrialSetup setup =
                trialSetupFor(result, ts.mode, spec.following, run.outline, ts.start);
            run.start = setup.start;
            progress.step = std::string(modeName(ts.mode)) + " following, " + ts.label + " trial " +
                            std::to_string(run.trial);
            int tapIndex = 0;
            run.result =
                runTrial(rig, result.classifier, result.classes, run.outline, setup,
                         [&](const FollowedTap& tap) {
                             if (recording)
                                 recording->append(run.label, ts.mode, run.trial, tapIndex, tap);
                             if (options.tapTaken)
                                 options.tapTaken(
                                     tap.record, std::string(modeName(ts.mode)) + " " + run.label +
                                                     " trial " + std::to_string(run.trial) + ": " +
                                                     tap.percept.shapeClass() + ", position " +
                                                     std::to_string(tap.percept.position) + " -> " +
                                                     ruleFor(tap.decision.rule).name);
                             ++tapIndex;
                             ++progress.tapsDone;
                             if (options.progress) options.progress(progress);
                             return !(options.cancel && options.cancel->load());
                         });
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
    if (!spec.recognition.enabled) return;
    // Templates at the centre of the valid range, one per distinct object followed.
    std::vector<NamedOutline> shapes;
    for (const TrialRun& run : result.trials) shapes.push_back({run.label, &run.outline});
    result.templates = shapeTemplates(
        shapes, 0.5 * (result.validOffsets.low + result.validOffsets.high),
        spec.following.followStep_mm, spec.recognition.bins, spec.recognition.smoothingSigmaBins);
    int recognised = 0, correct = 0, correctSmoothed = 0;
    for (TrialRun& run : result.trials) {
        if (run.result.mode != spec.recognition.ofMode) continue;
        run.recognised = true;
        run.recognition =
            recognise(run.result.path(), result.templates, spec.recognition.smoothingSigmaBins);
        ++recognised;
        correct += run.recognition.predicted == run.label;
        correctSmoothed += run.recognition.predictedSmoothed == run.label;
    }
    if (recognised > 0) {
        result.recognitionAccuracy = double(correct) / recognised;
        result.recognitionAccuracySmoothed = double(correctSmoothed) / recognised;
    }
}

}  // namespace

void checkRecordingCovers(const ExperimentSpec& spec, const std::vector<CollectedTap>& taps,
                          int taxels, const std::string& name) {
    const ClassSet& classes = spec.classes;
    const int sets = spec.training.dataSets;
    std::vector<std::vector<int>> count(static_cast<std::size_t>(sets) + 1,
                                        std::vector<int>(classes.classCount(), 0));
    bool anyTest = false;
    for (const CollectedTap& t : taps) {
        if (t.dataSet < 1 || t.dataSet > sets)
            throw InputError(name, "column set",
                             "data set " + std::to_string(t.dataSet) +
                                 " is not one of the experiment's data sets 1.." +
                                 std::to_string(sets) +
                                 "; use the experiment the taps were "
                                 "recorded with, or set training.data_sets");
        if (t.record.tap.taxels != taxels)
            throw InputError(name, "taxel columns",
                             "the taps have " + std::to_string(t.record.tap.taxels) +
                                 " taxels and the experiment's fingertip " +
                                 std::to_string(taxels) +
                                 "; use the fingertip description the taps were recorded with");
        ++count[static_cast<std::size_t>(t.dataSet)][static_cast<std::size_t>(t.cls)];
        anyTest = anyTest || !spec.training.isTrainingSet(t.dataSet);
    }
    for (int set : spec.training.trainingSets)
        for (int c = 0; c < classes.classCount(); ++c)
            if (count[static_cast<std::size_t>(set)][static_cast<std::size_t>(c)] == 0)
                throw InputError(
                    name, "data set " + std::to_string(set),
                    "training set " + std::to_string(set) + " has no tap of class " +
                        std::to_string(c) + " (" +
                        ClassSet::orientationName(classes.orientationDegOf(c)) +
                        " edge, position " + std::to_string(classes.positionOf(c)) +
                        "); every class needs a training tap: record it, or train on other sets "
                        "(training.training_sets)");
    if (!anyTest)
        throw InputError(name, "column set",
                         "every tap belongs to a training set, so nothing is left to validate on; "
                         "record test sets, or train on fewer sets (training.training_sets)");
}

RunResult runExperiment(const ExperimentSpec& specIn, const RunOptions& options) {
    const auto started = std::chrono::steady_clock::now();
    RunResult result;
    result.spec = specIn;
    if (options.seed) result.spec.scene.seed = *options.seed;
    const ExperimentSpec& spec = result.spec;

    auto model = std::make_shared<const FingertipContactModel>(spec.scene.fingertip);
    const std::vector<CollectedTap>* recorded = options.recordedTaps;
    if (recorded) checkRecordingCovers(spec, *recorded, model->taxelCount(), options.recordingName);
    // A replay's trials: each of the experiment's trials has its recording, of one tap shape.
    std::vector<const RecordedTrial*> replayed;
    if (recorded && options.recordedTrials) {
        replayed = replayedTrialsFor(spec, *options.recordedTrials, options.recordingName);
        const Tap& first = recorded->front().record.tap;
        for (const RecordedTrial* t : replayed)
            for (const TapRecord& r : t->taps)
                if (r.tap.taxels != first.taxels || r.tap.sampleCount() != first.sampleCount())
                    throw InputError(
                        options.recordingName,
                        std::string(modeName(t->mode)) + " " + t->label + " trial " +
                            std::to_string(t->trial),
                        "its taps have " + std::to_string(r.tap.taxels) + " taxels and " +
                            std::to_string(r.tap.sampleCount()) +
                            " samples, the training and test taps " + std::to_string(first.taxels) +
                            " and " + std::to_string(first.sampleCount()) +
                            "; replay a run whose recordings were taken with one fingertip and "
                            "tap window");
    }
    if (options.connected) checkRunnableOn(spec, *options.connected);
    std::unique_ptr<SceneRig> simulated;
    if (!options.connected && !recorded) simulated = simulatedRigsOf(options).build(spec.scene, model);
    if (simulated) {
        result.activeEffects = simulated->activeEffects();
    } else if (recorded) {
        result.rig = (options.recordedTrials ? "replay of " : "recording ") + options.recordingName;
    } else {
        result.rig = options.connected->description;
    }
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
    auto onTap = [&](const CollectedTap& tap) {
        if (recording) recording->append(tap, result.classes);
        if (options.tapTaken)
            options.tapTaken(
                tap.record,
                "training set " + std::to_string(tap.dataSet) + ": " +
                    ClassSet::orientationName(result.classes.orientationDegOf(tap.cls)) +
                    " edge, position " + std::to_string(result.classes.positionOf(tap.cls)));
        ++progress.tapsDone;
        if (options.progress) options.progress(progress);
        return !(options.cancel && options.cancel->load());
    };
    if (recorded) {
        for (const CollectedTap& tap : *recorded) {
            result.taps.push_back(tap);
            if (!onTap(tap)) break;
        }
        if (!result.taps.empty())
            result.robotTime_s =
                result.taps.back().record.startTime_s - result.taps.front().record.startTime_s;
    } else {
        Rig rig = options.connected ? options.connected->rig : simulated->rig();
        const double robotStart_s = rig.clock.now_s();
        result.taps = collectTrainingTaps(
            rig, simulated ? simulated->object() : spec.scene.object.outline(),
            result.classes, spec.training,
            RandomStream::derived(spec.scene.seed, "protocol:placement"), onTap);
        result.robotTime_s = rig.clock.now_s() - robotStart_s;
    }
    if (simulated) result.tapsSimulated = simulated->tapsSimulated();
    if (recorded ? result.taps.size() < recorded->size()
                 : static_cast<std::int64_t>(result.taps.size()) < spec.plannedTaps()) {
        result.cancelled = true;
        result.runWall_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        return result;
    }

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
    result.validation =
        validateOffline(result.classifier, result.classes, tests, spec.validRangeWidth);
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

    if (recorded) {
        // A recording is analysed offline: its trials, if any, replay on the recorded taps, and
        // of the sweeps only the one on the recorded taps themselves runs.
        if (!replayed.empty() && !result.cancelled)
            runTrials(result, model, options, progress, replayed);
        if (!spec.sweeps.bins.empty() && !result.cancelled && result.failure.empty()) {
            progress.step = "compute sweep on the recorded taps";
            if (options.progress) options.progress(progress);
            result.sweeps = runSweeps(result, options, true);
        }
        result.runWall_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        return result;
    }
    runTrials(result, model, options, progress);
    if (spec.sweeps.any() && !result.cancelled && result.failure.empty()) {
        progress.step = "accuracy-versus-time sweeps";
        if (options.progress) options.progress(progress);
        result.sweeps = runSweeps(result, options);
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
    auto model = std::make_shared<const FingertipContactModel>(result.spec.scene.fingertip);
    RunProgress progress;
    progress.tapsPlanned =
        static_cast<int>(plannedTapEstimate(result.spec) - result.spec.plannedTaps());
    runTrials(result, model, options, progress);
    result.runWall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

void printTrialTaps(OutputFile& f, const std::string& prefix, const TrialRun& t) {
    int i = 0;
    for (const auto& tap : t.result.taps) {
        const Vec2 m = tap.decision.move();
        f.print("%s%d,%.10g,%.10g,%s,%g,%d,%s,%.10g,%.10g,%.10g,%.10g\n", prefix.c_str(), i++,
                tap.record.pose.x, tap.record.pose.y, tap.percept.shapeClass().c_str(),
                tap.percept.orientationDeg, tap.percept.position, ruleFor(tap.decision.rule).name,
                m.x, m.y, tap.progress_mm, tap.contourDistance_mm);
    }
}

void writeRunTables(const RunResult& r, const std::string& outDir) {
    const fs::path data = fs::path(outDir) / "data";
    ensureOutputDirectory(data.string());
    const ClassSet& cs = r.classes;

    {
        OutputFile f((data / "class_regions.csv").string());
        f.print("class,orientation_deg,orientation,position,offset_mm,region\n");
        for (int c = 0; c < cs.classCount(); ++c)
            f.print("%d,%g,%s,%d,%g,%s\n", c, cs.orientationDegOf(c),
                    ClassSet::orientationName(cs.orientationDegOf(c)).c_str(), cs.positionOf(c),
                    cs.offsetOf(cs.positionOf(c)), regionName(cs.regionOf(c)));
        f.close();
    }
    if (!r.validation.byClass.empty()) {
        {
            OutputFile f((data / "validation_by_class.csv").string());
            f.print(
                "orientation_deg,orientation,position,region,test_taps,angle_error_deg,"
                "position_error_mm,correct_fraction\n");
            for (const auto& e : r.validation.byClass) {
                const double deg = cs.orientationsDeg[static_cast<std::size_t>(e.orientationIndex)];
                f.print("%g,%s,%d,%s,%d,%.10g,%.10g,%.10g\n", deg,
                        ClassSet::orientationName(deg).c_str(), e.position, regionName(e.region),
                        e.taps, e.angleError_deg, e.positionError_mm, e.correctFraction);
            }
            f.close();
        }

        {
            OutputFile f((data / "validation_by_position.csv").string());
            f.print(
                "position,offset_mm,angle_error_deg_mean,angle_error_deg_std,position_error_"
                "mm_mean,position_error_mm_std,in_valid_range\n");
            for (int p = 1; p <= cs.positions; ++p) {
                const auto i = static_cast<std::size_t>(p - 1);
                f.print("%d,%g,%.10g,%.10g,%.10g,%.10g,%d\n", p, cs.offsetOf(p),
                        r.validation.angleMean[i], r.validation.angleStd[i],
                        r.validation.positionMean[i], r.validation.positionStd[i],
                        p >= r.validation.validRange.first && p <= r.validation.validRange.last
                            ? 1
                            : 0);
            }
            f.close();
        }

        {
            OutputFile f((data / "test_percepts.csv").string());
            f.print(
                "set,true_class,true_orientation_deg,true_position,true_offset_mm,perceived_"
                "class,shape_class,perceived_orientation_deg,perceived_position,posterior\n");
            std::size_t i = 0;
            for (const auto& t : r.taps) {
                if (r.spec.training.isTrainingSet(t.dataSet)) continue;
                const Percept& p = r.validation.percepts[i++];
                f.print("%d,%d,%g,%d,%.10g,%d,%s,%g,%d,%.10g\n", t.dataSet, t.cls,
                        cs.orientationDegOf(t.cls), cs.positionOf(t.cls), t.trueOffset_mm, p.cls,
                        p.shapeClass().c_str(), p.orientationDeg, p.position, p.posterior);
            }
            f.close();
        }
    }
    if (!r.trials.empty()) {
        {
            OutputFile f((data / "following_trials.csv").string());
            f.print(
                "shape,mode,trial,completed,end,taps,robot_time_s,coverage,mean_contour_"
                "distance_mm,max_contour_distance_mm,progress_mm,start_x_mm,start_y_mm,"
                "furthest_progress_mm,furthest_x_mm,furthest_y_mm,furthest_place,corner_x_mm,"
                "corner_y_mm,past_corner_mm,convex_corners_rounded,concave_corners_rounded\n");
            for (const auto& t : r.trials) {
                const ContourPlace& at = t.result.furthest;
                f.print("%s,%s,%d,%d,%s,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s,",
                        t.label.c_str(), modeName(t.result.mode), t.trial,
                        t.result.completed() ? 1 : 0, trialEndName(t.result.end),
                        t.result.taps.size(), t.result.robotTime_s, t.result.coverage,
                        t.result.meanContourDistance_mm, t.result.maxContourDistance_mm,
                        t.result.progress_mm, t.start.x, t.start.y, t.result.furthestProgress_mm,
                        at.point.x, at.point.y, placeKindName(at.kind));
                if (at.kind == PlaceKind::AwayFromCorners)
                    f.print(",,");
                else
                    f.print("%.6g,%.6g,%.6g", at.corner.x, at.corner.y, at.pastCorner_mm);
                f.print(",%d,%d\n", t.result.cornersRounded.convex,
                        t.result.cornersRounded.concave);
            }
            f.close();
        }
        {
            OutputFile f((data / "following_paths.csv").string());
            f.print("shape,mode,trial,%s\n", kTrialTapColumns);
            for (const auto& t : r.trials)
                printTrialTaps(
                    f,
                    t.label + "," + modeName(t.result.mode) + "," + std::to_string(t.trial) + ",",
                    t);
            f.close();
        }
        {
            OutputFile f((data / "outlines.csv").string());
            f.print("shape,vertex,x_mm,y_mm\n");
            std::map<std::string, bool> written;
            for (const auto& t : r.trials) {
                if (written[t.label]) continue;
                written[t.label] = true;
                for (std::size_t v = 0; v < t.outline.size(); ++v)
                    f.print("%s,%zu,%.10g,%.10g\n", t.label.c_str(), v, t.outline.vertex(v).x,
                            t.outline.vertex(v).y);
            }
            f.close();
        }
    }
    if (!r.templates.empty()) {
        {
            OutputFile f((data / "recognition.csv").string());
            f.print("shape,trial,predicted,predicted_smoothed");
            for (const auto& t : r.templates) f.print(",distance_%s", t.shape.c_str());
            for (const auto& t : r.templates) f.print(",smoothed_distance_%s", t.shape.c_str());
            f.put('\n');
            for (const auto& t : r.trials) {
                if (!t.recognised) continue;
                f.print("%s,%d,%s,%s", t.label.c_str(), t.trial, t.recognition.predicted.c_str(),
                        t.recognition.predictedSmoothed.c_str());
                for (const auto& tp : r.templates)
                    f.print(",%.10g", t.recognition.distances.at(tp.shape));
                for (const auto& tp : r.templates)
                    f.print(",%.10g", t.recognition.smoothedDistances.at(tp.shape));
                f.put('\n');
            }
            f.close();
        }
        {
            OutputFile f((data / "path_histograms.csv").string());
            f.print("kind,shape,trial,smoothed,ix,iy,value\n");
            auto dump = [&](const char* kind, const std::string& shape, int trial, bool smooth,
                            const PathHistogram& h) {
                for (int iy = 0; iy < h.bins; ++iy)
                    for (int ix = 0; ix < h.bins; ++ix)
                        f.print("%s,%s,%d,%d,%d,%d,%.10g\n", kind, shape.c_str(), trial,
                                smooth ? 1 : 0, ix, iy, h.at(ix, iy));
            };
            for (const auto& t : r.templates) {
                dump("template", t.shape, 0, false, t.raw);
                dump("template", t.shape, 0, true, t.smooth);
            }
            for (const auto& t : r.trials)
                if (t.recognised) {
                    dump("path", t.label, t.trial, false, t.recognition.raw);
                    dump("path", t.label, t.trial, true, t.recognition.smooth);
                }
            f.close();
        }
    }

    const SweepResults& sw = r.sweeps;
    if (!sw.perception.empty()) {
        {
            OutputFile f((data / "sweep_perception.csv").string());
            f.print(
                "belief_threshold,mean_taps_per_decision,angle_error_deg,position_error_mm,"
                "correct_fraction\n");
            for (const auto& row : sw.perception)
                f.print("%.15g,%.6g,%.6g,%.6g,%.6g\n", row.threshold, row.meanTaps,
                        row.angleError_deg, row.positionError_mm, row.correctFraction);
            f.close();
        }
    }
    if (!sw.following.empty()) {
        {
            OutputFile f((data / "sweep_following.csv").string());
            f.print(
                "mode,follow_step_mm,reposition_step_mm,belief_threshold,trials,completed,"
                "completion_rate,mean_contour_distance_mm,"
                "mean_taps,mean_robot_time_s,robot_time_per_completion_s,paper_setting\n");
            for (const auto& row : sw.following)
                f.print("%s,%g,%g,%.15g,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%d\n", modeName(row.mode),
                        row.followStep_mm, row.repositionStep_mm, row.beliefThreshold, row.trials,
                        row.completed, double(row.completed) / row.trials,
                        row.meanContourDistance_mm, row.meanTaps, row.meanRobotTime_s,
                        row.robotTimePerCompletion_s, row.paperSetting ? 1 : 0);
            f.close();
        }
    }
    if (!sw.compute.empty()) {
        {
            OutputFile f((data / "sweep_compute.csv").string());
            f.print(
                "bins,samples_per_tap,angle_error_deg,position_error_mm,microseconds_per_"
                "decision,paper_setting\n");
            for (const auto& row : sw.compute)
                f.print("%d,%d,%.6g,%.6g,%.6g,%d\n", row.bins, row.samples, row.angleError_deg,
                        row.positionError_mm, row.microsecondsPerDecision,
                        row.paperSetting ? 1 : 0);
            f.close();
        }
    }

    if (r.validation.confusion.empty()) return;
    {
        OutputFile f((data / "confusion.csv").string());
        f.print("true_class");
        for (int c = 0; c < cs.classCount(); ++c) f.print(",perceived_%d", c);
        f.put('\n');
        for (int a = 0; a < cs.classCount(); ++a) {
            f.print("%d", a);
            for (int b = 0; b < cs.classCount(); ++b)
                f.print(",%d",
                        r.validation.confusion[static_cast<std::size_t>(a * cs.classCount() + b)]);
            f.put('\n');
        }
        f.close();
    }
}

namespace {

/// Where a trial got furthest along the contour: the point, its progress and its place.
Json placeJson(const TrialResult& t) {
    const ContourPlace& at = t.furthest;
    Json j{{"progress_mm", t.furthestProgress_mm},
           {"point_mm", {at.point.x, at.point.y}},
           {"place", placeKindName(at.kind)},
           {"description", describePlace(at)}};
    if (at.kind != PlaceKind::AwayFromCorners) {
        j["corner_mm"] = {at.corner.x, at.corner.y};
        j["past_corner_mm"] = at.pastCorner_mm;
    }
    return j;
}

}  // namespace

Json summaryJson(const RunResult& r, double wall_s, double figures_s) {
    const ClassSet& cs = r.classes;
    Json j;
    j["experiment"] = r.spec.name;
    j["source"] = r.spec.source;
    j["seed"] = r.spec.scene.seed;
    j["run_finished"] = !r.cancelled && r.failure.empty();
    j["scene"] = sceneToJson(r.spec.scene);
    j["effects_active"] = r.activeEffects;
    j["rig"] = r.rig;
    Json regions = Json::array();
    for (int c = 0; c < cs.classCount(); ++c) regions.push_back(regionName(cs.regionOf(c)));
    j["noise_floor"] = {
        {"counts", r.noiseFloor_counts},
        {"scene_counts", r.spec.scene.tap.noiseFloor},
        {"measured_counts",
         r.measuredNoiseFloor ? Json(r.measuredNoiseFloor->counts) : Json(nullptr)},
        {"measured_from_taps", r.measuredNoiseFloor ? r.measuredNoiseFloor->taps : 0},
        {"rule",
         "95th percentile of the peak reading of the taps at classes whose ideal tap touches "
         "nothing, never below the scene's noise_floor_counts; classes whose ideal peak pressure "
         "is below it are air"}};
    j["classes"] = {{"orientations_deg", cs.orientationsDeg},
                    {"positions", cs.positions},
                    {"position_step_mm", cs.positionStep_mm},
                    {"regions", regions}};
    j["classifier"] = {{"bins", r.spec.classifier.bins},
                       {"smoothing", r.spec.classifier.smoothing},
                       {"kernel_sigma_bins", r.spec.classifier.kernelSigma_bins}};
    j["training"] = {{"data_sets", r.spec.training.dataSets},
                     {"training_sets", r.spec.training.trainingSets},
                     {"taps_per_class", r.spec.training.tapsPerClass},
                     {"test_offset_mm", r.spec.training.testOffset_mm},
                     {"placement_jitter_mm", r.spec.training.placementJitter_mm},
                     {"retrain_on_all_sets", r.spec.training.retrainOnAllSets}};
    if (!r.validation.byClass.empty()) {
        const auto& v = r.validation;
        Json byClass = Json::array();
        for (const auto& e : v.byClass) {
            const double deg = cs.orientationsDeg[static_cast<std::size_t>(e.orientationIndex)];
            byClass.push_back({{"orientation_deg", deg},
                               {"orientation", ClassSet::orientationName(deg)},
                               {"position", e.position},
                               {"region", regionName(e.region)},
                               {"test_taps", e.taps},
                               {"angle_error_deg", e.angleError_deg},
                               {"position_error_mm", e.positionError_mm},
                               {"correct_fraction", e.correctFraction}});
        }
        Json byPosition = Json::array();
        for (int p = 1; p <= cs.positions; ++p) {
            const auto i = static_cast<std::size_t>(p - 1);
            byPosition.push_back({{"position", p},
                                  {"angle_error_deg_mean", v.angleMean[i]},
                                  {"angle_error_deg_std", v.angleStd[i]},
                                  {"position_error_mm_mean", v.positionMean[i]},
                                  {"position_error_mm_std", v.positionStd[i]}});
        }
        j["validation"] = {
            {"angle_error_deg_mean", v.angleError_deg},
            {"position_error_mm_mean", v.positionError_mm},
            {"class_accuracy", v.correctFraction},
            {"valid_range_mm",
             {v.validRange.first * cs.positionStep_mm, v.validRange.last * cs.positionStep_mm}},
            {"valid_range_positions", {v.validRange.first, v.validRange.last}},
            {"valid_range_offset_mm",
             {cs.offsetOf(v.validRange.first), cs.offsetOf(v.validRange.last)}},
            {"valid_range_rule", "the window of " + std::to_string(r.spec.validRangeWidth) +
                                     " consecutive positions with the lowest sum of "
                                     "orientation-averaged angle and position errors, "
                                     "each normalised by its maximum over positions; ties to the "
                                     "window nearest the edge"},
            {"test_taps", v.percepts.size()},
            {"by_class", byClass},
            {"by_position", byPosition}};
    }
    if (!r.failure.empty()) j["failure"] = r.failure;
    j["cautions"] = untrainedEdgeCautions(r.spec);
    j["controller"] = {
        {"valid_offsets_mm", {r.validOffsets.low, r.validOffsets.high}},
        {"orientation_trusted_positions", {r.trustedPositions.first, r.trustedPositions.second}},
        {"orientation_trusted_offsets_mm", {r.validOffsets.trustedLow, r.validOffsets.trustedHigh}},
        {"orientation_trust_max_error_deg", r.spec.following.orientationTrustMaxError_deg}};
    Json following = Json::array();
    for (const auto& t : r.trials) {
        following.push_back({{"shape", t.label},
                             {"mode", modeName(t.result.mode)},
                             {"trial", t.trial},
                             {"completed", t.result.completed()},
                             {"reason", trialEndName(t.result.end)},
                             {"detail", t.result.detail},
                             {"taps", t.result.taps.size()},
                             {"robot_time_s", t.result.robotTime_s},
                             {"coverage", t.result.coverage},
                             {"mean_contour_distance_mm", t.result.meanContourDistance_mm},
                             {"max_contour_distance_mm", t.result.maxContourDistance_mm},
                             {"progress_mm", t.result.progress_mm},
                             {"start_mm", {t.start.x, t.start.y}},
                             {"furthest", placeJson(t.result)},
                             {"corners_rounded",
                              {{"convex", t.result.cornersRounded.convex},
                               {"concave", t.result.cornersRounded.concave}}}});
        if (t.recordedTaps >= 0) following.back()["recorded_taps"] = t.recordedTaps;
    }
    j["following"] = following;
    if (!r.templates.empty()) {
        Json trials = Json::array();
        std::map<std::string, std::map<std::string, int>> confusion, confusionSmoothed;
        for (const auto& t : r.trials) {
            if (!t.recognised) continue;
            trials.push_back({{"shape", t.label},
                              {"trial", t.trial},
                              {"predicted", t.recognition.predicted},
                              {"predicted_smoothed", t.recognition.predictedSmoothed},
                              {"distances", t.recognition.distances},
                              {"smoothed_distances", t.recognition.smoothedDistances}});
            ++confusion[t.label][t.recognition.predicted];
            ++confusionSmoothed[t.label][t.recognition.predictedSmoothed];
        }
        j["recognition"] = {{"accuracy", r.recognitionAccuracy},
                            {"accuracy_smoothed", r.recognitionAccuracySmoothed},
                            {"of_mode", modeName(r.spec.recognition.ofMode)},
                            {"bins", r.spec.recognition.bins},
                            {"smoothing_sigma_bins", r.spec.recognition.smoothingSigmaBins},
                            {"trials", trials},
                            {"confusion", confusion},
                            {"confusion_smoothed", confusionSmoothed}};
    }
    if (!r.sweeps.empty()) {
        Json perception = Json::array(), following = Json::array(), compute = Json::array();
        for (const auto& row : r.sweeps.perception)
            perception.push_back({{"belief_threshold", row.threshold},
                                  {"mean_taps_per_decision", row.meanTaps},
                                  {"angle_error_deg", row.angleError_deg},
                                  {"position_error_mm", row.positionError_mm},
                                  {"correct_fraction", row.correctFraction}});
        for (const auto& row : r.sweeps.following)
            following.push_back(
                {{"mode", modeName(row.mode)},
                 {"follow_step_mm", row.followStep_mm},
                 {"reposition_step_mm", row.repositionStep_mm},
                 {"belief_threshold", row.beliefThreshold},
                 {"trials", row.trials},
                 {"completed", row.completed},
                 {"mean_contour_distance_mm", row.meanContourDistance_mm},
                 {"mean_taps", row.meanTaps},
                 {"mean_robot_time_s", row.meanRobotTime_s},
                 {"robot_time_per_completion_s", std::isfinite(row.robotTimePerCompletion_s)
                                                     ? Json(row.robotTimePerCompletion_s)
                                                     : Json()},
                 {"paper_setting", row.paperSetting}});
        for (const auto& row : r.sweeps.compute)
            compute.push_back({{"bins", row.bins},
                               {"samples_per_tap", row.samples},
                               {"angle_error_deg", row.angleError_deg},
                               {"position_error_mm", row.positionError_mm},
                               {"microseconds_per_decision", row.microsecondsPerDecision},
                               {"paper_setting", row.paperSetting}});
        j["sweeps"] = {{"perception", perception}, {"following", following}, {"compute", compute}};
    }
    j["timing"] = {{"wall_s", wall_s},
                   {"run_wall_s", r.runWall_s},
                   {"figures_wall_s", figures_s},
                   {"taps_simulated", r.tapsSimulated},
                   {"robot_time_s", r.robotTime_s}};
    return j;
}

void writeSummary(const RunResult& r, const std::string& outDir, double wall_s, double figures_s) {
    Json summary = summaryJson(r, wall_s, figures_s);
    // The run that claimed the folder: replay refuses a summary of another run beside its data.
    if (const std::string id = runIdOf(outDir); !id.empty()) summary["run_id"] = id;
    writeJsonAtomically((fs::path(outDir) / "summary.json").string(), summary);
}

}  // namespace activetouch
