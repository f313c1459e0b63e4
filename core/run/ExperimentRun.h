#pragma once
// Running an experiment end to end, on the simulated rig or on a connected one, and writing its
// artefacts (docs/design.md §5): summary.json, data/*.csv (taps appended as they are taken), and
// the tables behind every figure. Figures are drawn by app/figures from the same result.
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/classify/BeliefCalibration.h"
#include "core/classify/HistogramClassifier.h"
#include "core/control/ContourFollower.h"
#include "core/experiment/Experiment.h"
#include "core/recognition/PathHistogram.h"
#include "core/recognition/PoseRecognition.h"
#include "core/records/FollowingRecording.h"
#include "core/rig/Rig.h"
#include "core/run/SimulatedRigs.h"
#include "core/run/SweepResults.h"
#include "core/validation/ClassRegions.h"
#include "core/validation/OfflineValidation.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {

struct RunProgress {
    int tapsDone = 0;
    int tapsPlanned = 0;
    std::string step;
};

/// The one way a run's taps reach anyone besides the recording: the window's live view and
/// progress bar, the command line's Ctrl-C. Every call comes on the thread that runs the
/// experiment, after the tap is recorded.
class RunObserver {
public:
    virtual ~RunObserver() = default;
    /// Which part of the run a tap belongs to: training and test taps are taken on a class the
    /// run chose; following taps are perceived.
    enum class Stage { Training, Following };
    /// A tap as it is taken, with a sentence saying what it was ("active cross trial 1: ...").
    virtual void tapTaken(const TapRecord& tap, const std::string& what, Stage stage) {
        (void)tap;
        (void)what;
        (void)stage;
    }
    /// How far the run has got: after every tap, and as each step begins.
    virtual void progressed(const RunProgress& progress) { (void)progress; }
    /// Asked after every tap: true stops the run there, keeping every tap taken.
    virtual bool stopRequested() const { return false; }
};

/// An observer that only stops the run when `flag` is set (Ctrl-C, a cancel button).
class StopFlag final : public RunObserver {
public:
    explicit StopFlag(const std::atomic<bool>& flag) : flag_(flag) {}
    bool stopRequested() const override { return flag_.load(); }

private:
    const std::atomic<bool>& flag_;
};

struct TrialRun {
    std::string label;
    int trial = 1;  ///< 1-based within its label and mode
    Polygon outline;
    double rotationDeg = 0.0;  ///< the object's turn (drawn from the seed for "random")
    Vec2 start;
    TrialResult result;
    bool recognised = false;
    Recognition recognition;
    PoseRecognition poseRecognition;  ///< at any pose, beside the paper's rule
    /// The object's frame origin on the stage, and where its outline's centroid lies: with
    /// rotationDeg, the truth poseRecognition's turn and place are judged against.
    Vec2 objectOffset, objectCentre;
    int recordedTaps = -1;  ///< replayed: the taps the recording holds for this trial
};

/// A connected rig (real devices, or any mix of real and simulated) to take every tap on instead
/// of the simulated rig. It holds one object: the one `object` describes.
struct ConnectedRig {
    Rig rig;
    ObjectSpec object;
    std::string description;  ///< "stage: Yamaha RCX on /dev/ttyUSB0; tapper: ..."
};

struct RunResult {
    ExperimentSpec spec;            ///< with the seed actually used
    std::string rig = "simulated";  ///< where the taps were taken
    ClassSet classes;               ///< with the region map
    /// The tap-level noise floor the region map and contact detection use, counts: the measured
    /// one (ClassRegions.h) where it lies above the scene's `noise_floor_counts`.
    double noiseFloor_counts = 0.0;
    std::optional<MeasuredNoiseFloor> measuredNoiseFloor;  ///< nothing: no tap touched nothing
    std::vector<std::string> activeEffects;
    std::vector<CollectedTap> taps;  ///< every tap, in order
    HistogramClassifier classifier;
    /// How many taps `classifier` was trained on again after validation (every data set's, with
    /// training.retrain_on_all_sets); 0: the trials follow with the validated classifier.
    int classifierRetrainedOnTaps = 0;
    ValidationResult validation;
    /// How far one tap's posterior can be believed, raw and scaled, on the held-out taps
    /// (core/classify/BeliefCalibration.h).
    BeliefCalibration beliefCalibration;
    ValidOffsets
        validOffsets;  ///< the valid range as offsets from the edge, used by the controller
    /// The fingertip's contact patch on an edge, as a radius (core/geometry/ContourReach.h): the
    /// contour it cannot resolve does not count toward a trial's coverage.
    double contactRadius_mm = 0.0;
    std::pair<int, int> trustedPositions{1,
                                         1};  ///< positions whose orientation the controller uses
    std::vector<TrialRun> trials;
    std::vector<ShapeTemplate> templates;
    std::vector<PoseTemplate> poseTemplates;
    double recognitionAccuracy = 0.0, recognitionAccuracySmoothed = 0.0;
    double recognitionAccuracyAnyPose = 0.0;
    /// Over trials named right at any pose whose shape has a turn: the median error of the
    /// recovered turn (modulo the shape's symmetry), degrees, and of the recovered place, mm.
    double medianRotationError_deg = 0.0, medianPositionError_mm = 0.0;
    /// The continuous percept along the trials' paths: the median angle error against the true
    /// local edge of the taps inside the valid range and away from corners (FollowedTap), and
    /// how many; -1 without such taps.
    double pathMedianAngleError_deg = -1.0;
    int pathAngleTaps = 0;
    SweepResults sweeps;
    std::string failure;  ///< a device error that stopped the run, if any
    bool cancelled = false;
    double robotTime_s = 0.0;
    std::uint64_t tapsSimulated = 0;
    double runWall_s = 0.0;  ///< simulation, training and validation
};

struct RunOptions {
    /// Builds the simulated rigs that training, trials and sweeps take their taps on unless
    /// `connected` or `recordedTaps` says otherwise (not owned): the window and the command line
    /// give devices/simulated's.
    const SimulatedRigs* simulated = nullptr;
    std::string outDir;  ///< empty: write nothing
    std::optional<std::uint64_t> seed;
    /// Hears every tap and the progress, and may stop the run (not owned; none: nobody listens).
    RunObserver* observer = nullptr;
    /// Take the taps on this rig instead of simulated ones (not owned; must outlive the run).
    const ConnectedRig* connected = nullptr;
    /// Re-analyse these recorded training and test taps instead of taking any (not owned): the
    /// run trains and validates on them and stops there (trials and sweeps need a rig).
    const std::vector<CollectedTap>* recordedTaps = nullptr;
    /// With recordedTaps: replay these recorded trials as rigs (not owned). Each trial of the
    /// experiment runs on its recorded namesake, served a recorded tap wherever the recorded run
    /// tapped; where it decides otherwise it leaves the recording (TrialEnd::LeftRecording).
    const std::vector<RecordedTrial>* recordedTrials = nullptr;
    std::string recordingName;  ///< where the recorded taps came from, for the summary
    /// Whether the caller reads RunResult::beliefCalibration (the window and `run` show and write
    /// it). A run over seeds keeps only its outcome: without it, the calibration is measured
    /// only where the trials or sweeps use it.
    bool reportsBeliefCalibration = true;
    /// Called once, after every input check and before the first file is written in outDir: a
    /// caller claims the folder there (RunFolder.h), so that a refused input writes nothing.
    std::function<void()> beforeWriting;
    /// Whether the observer asked the run to stop.
    bool stopRequested() const { return observer && observer->stopRequested(); }
};

/// `options.simulated`; throws std::logic_error when a run that needs simulated rigs was given
/// none.
const SimulatedRigs& simulatedRigsOf(const RunOptions& options);

/// Refuses, before any tap, what cannot run on `connected`: a scene or trial whose object is not
/// the one mounted there, or a sweep (sweeps replay on simulated rigs). Throws InputError naming
/// the trial and what to do.
void checkRunnableOn(const ExperimentSpec& spec, const ConnectedRig& connected);
/// The same for a rig with `object` mounted, before its devices are connected.
void checkRunnableOn(const ExperimentSpec& spec, const ObjectSpec& object);

/// Runs the experiment's steps: training and validation taps (appended to <outDir>/data/taps.csv
/// as they are taken, or the recorded ones of `options.recordedTaps`), then the contour-following
/// trials (appended to <outDir>/data/following_taps.csv), then recognition of the traced paths. A
/// device error during the training taps throws RigError; during a trial it ends that trial, is
/// noted in `failure`, and stops the run with everything recorded so far. InputError if the output
/// cannot be written.
RunResult runExperiment(const ExperimentSpec& spec, const RunOptions& options);

/// runExperiment for runs over seeds: a device or rig error during the training taps, which
/// runExperiment throws, comes back as a result with `failure` set and no trials, as one during a
/// trial does, so that the run counts as failed and never as trials lost.
RunResult runExperimentOrFailure(const ExperimentSpec& spec, const RunOptions& options);

/// What the trials follow with when it is not the validated classifier: a sentence saying the
/// classifier was trained again on every data set after validation, or empty.
std::string followingClassifierNote(const RunResult& result);

/// The settings that decide what a classifier is — classes, classifier, training protocol, valid
/// range width — in which `spec` differs from those `trained` was trained with, one "what: then ->
/// now" line each; empty when following `spec` with `trained`'s classifier follows as it says.
std::vector<std::string> trainingSettingsChanged(const RunResult& trained,
                                                 const ExperimentSpec& spec);

/// Runs only the following trials (and recognition) of `spec` with the classifier, class regions
/// and valid range of an earlier run.
RunResult runFollowing(const RunResult& trained, const ExperimentSpec& spec,
                       const RunOptions& options);

/// A trial's set-up on `outline` with a trained run's valid range: the given start, or the lower
/// edge's middle centred in the valid range.
TrialSetup trialSetupFor(const RunResult& trained, FollowingMode mode,
                         const FollowingSettings& settings, const Polygon& outline,
                         const std::optional<Vec2>& start);

/// How many taps a run will take: exact for training, estimated for following trials.
int plannedTapEstimate(const ExperimentSpec& spec);

}  // namespace activetouch
