#pragma once
// An experiment file: a scene plus the protocol to run on it (docs/design.md §5). The paper's
// experiment is experiments/paper.json.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/classify/HistogramClassifier.h"
#include "core/control/FollowingSettings.h"
#include "core/scene/Scene.h"
#include "core/tap/ClassSet.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {

/// A set of contour-following trials on one object.
struct TrialSpec {
    std::string label;  ///< the shape's name for recognition (default: the library shape)
    FollowingMode mode = FollowingMode::Active;
    ObjectSpec object;
    int repeats = 1;
    std::optional<Vec2> start;  ///< default: the lower edge's middle, centred in the valid range
    std::string place;          ///< JSON pointer, for errors
};

struct RecognitionSpec {
    bool enabled = false;
    int bins = 20;
    double smoothingSigmaBins = 1.0;  ///< for the smoothed histogram reported beside the paper's
    FollowingMode ofMode = FollowingMode::Active;
};

/// Accuracy-versus-time sweeps (docs/accuracy-vs-time.md); each part runs only if given.
struct SweepSpec {
    // (a) sequential perception: error vs mean taps per decision over belief thresholds
    std::vector<double> beliefThresholds;
    int tapsPerClass = 8;  ///< repeated taps per class collected for the sweep
    int maxTapsPerDecision = 8;
    // (b) contour following vs follow step, repositioning step and belief threshold
    std::vector<double> followSteps_mm, repositionSteps_mm, followingBeliefThresholds;
    std::vector<FollowingMode> modes;
    int followingRepeats = 1;  ///< trials per object per setting
    // (c) compute: classifier error vs bins and samples per tap, against microseconds per decision
    std::vector<int> bins, samplesPerTap;
    // (d) a bandit learning the operating point among (b)'s active settings by reward: each
    // trial's reward is 1 if it completed, less its robot time over completionWorth_s.
    bool bandit = false;
    int banditRounds = 0;  ///< trials the learner runs; 0: four per setting
    double completionWorth_s = 2000.0;
    // (e) robustness: the whole run again on the same seed, with one fault added to the scene
    // (an effect of the same name replaced), against active completion and recognition.
    struct Fault {
        std::string name;  ///< "dead taxel 3", "gain spread 0.2", "crosstalk 0.1"
        EffectSpec effect;
    };
    std::vector<Fault> faults;

    bool any() const {
        return !beliefThresholds.empty() || !followSteps_mm.empty() || !bins.empty() ||
               !faults.empty();
    }
};

struct ExperimentSpec {
    std::string source;
    std::string name;
    std::string description;
    SceneSpec scene;
    ClassSet classes;
    ClassifierSettings classifier;
    TrainingProtocolSettings training;
    int validRangeWidth = 4;  ///< positions in the valid range window
    FollowingSettings following;
    std::vector<TrialSpec> trials;
    RecognitionSpec recognition;
    SweepSpec sweeps;

    std::int64_t plannedTaps() const;  ///< training taps; trials add theirs as they go
};

/// Why training on the scene's object cannot run as the experiment says, or empty (see
/// trainingPosesProblem). The parser refuses such an experiment; so does the window for a scene
/// edited in its panel.
std::string trainingObjectProblem(const ExperimentSpec& e);

/// The trials whose objects have edges facing none of the classes' orientations (more than
/// `toleranceDeg` off the nearest), one line each naming the trial, how many edges and the worst.
/// Such an experiment runs, but every percept snaps the follow direction to a trained
/// orientation, so the follower degrades along those edges: `check`, `run` and the window say so
/// before any tap. None for the continuous percept, which reads angles between the trained ones.
std::vector<std::string> untrainedEdgeCautions(const ExperimentSpec& e, double toleranceDeg = 5.0);

/// Parses an experiment; the scene may be inline or a path relative to the experiment file.
ExperimentSpec parseExperiment(const Json& json, const std::string& source,
                               const std::string& baseDirectory);
ExperimentSpec loadExperiment(const std::string& path);

/// An experiment file's document with "extends" resolved: a file may name the experiment it
/// builds on ("extends": path relative to it) and give only what differs; its keys patch the
/// base's (RFC 7386 merge patch: objects merge key by key, null removes a key, lists and values
/// replace). A scene path is taken relative to the file that names it. Throws InputError for a
/// file that is no experiment, a missing base or a circle of extends.
Json readExperimentFile(const std::string& path);

/// Whether a JSON file is an experiment (has "scene" or "extends") or a bare scene.
bool looksLikeExperiment(const Json& json);

}  // namespace activetouch
