#include "core/experiment/Experiment.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/common/NumberText.h"
#include "core/control/ContourFollower.h"
#include "core/experiment/ExperimentSweeps.h"

namespace activetouch {
namespace fs = std::filesystem;

bool looksLikeExperiment(const Json& json) {
    return json.is_object() && (json.contains("scene") || json.contains("extends"));
}

std::int64_t ExperimentSpec::plannedTaps() const {
    return std::int64_t{training.dataSets} * classes.classCount() * training.tapsPerClass;
}

namespace {

FollowingMode parseMode(const JsonFields& f, const std::string& key, const std::string& fallback) {
    const std::string m = f.text(key, fallback);
    if (const auto mode = modeNamed(m)) return *mode;
    f.fail(key, "mode '" + m + "' is neither active nor passive");
}

/// One trial of the following section's list, at `place`.
TrialSpec parseTrial(const JsonFields& t, const std::string& place, const ExperimentSpec& e,
                     const std::string& baseDirectory) {
    t.rejectUnknownKeys({"label", "mode", "object", "repeats", "start_mm"});
    TrialSpec spec;
    spec.place = place;
    spec.mode = parseMode(t, "mode", "active");
    spec.object = parseObject(t.object("object"), baseDirectory);
    spec.label = t.text("label", spec.object.shape);
    const bool control = std::any_of(spec.label.begin(), spec.label.end(), [](char c) {
        return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    });
    if (spec.label.empty() || control || spec.label.find_first_of(",\"\r\n") != std::string::npos)
        t.fail("label",
               "'" + spec.label +
                   "' cannot name a trial: labels go into the run's CSV files as they are, so "
                   "give a name without commas, quotes, line breaks or other control "
                   "characters");
    spec.repeats = t.integer("repeats", 1, 1000, 1);
    if (const std::string problem = objectPlacementProblem(spec.object, e.scene); !problem.empty())
        throw InputError(t.source(), place + "/object", problem);
    for (const Polygon& outline : spec.object.possibleOutlines())
        if (const std::string problem =
                followingTravelProblem(outline, e.following, e.scene.stage.travel_mm);
            !problem.empty())
            throw InputError(t.source(), place + "/object",
                             "trial '" + spec.label + "'" +
                                 (spec.object.rotationDrawn ? " (turned any way)" : "") + ": " +
                                 problem);
    if (t.has("start_mm")) {
        spec.start = t.point("start_mm");
        if (const std::string problem =
                startProblem(spec.object.outline(), *spec.start, e.following);
            !problem.empty())
            t.fail("start_mm", problem);
    } else {
        try {
            lowerEdgeStart(spec.object.outline(), ValidOffsets{});
        } catch (const std::invalid_argument& err) {
            t.fail("object", std::string(err.what()) + "; give start_mm");
        }
    }
    return spec;
}

void parseFollowingSettings(const JsonFields& f, FollowingSettings& s) {
    f.rejectUnknownKeys({"follow_step_mm",
                         "reposition_step_mm",
                         "plane_step_mm",
                         "plane_retreat_step_mm",
                         "air_inward_step_mm",
                         "air_retreat_step_mm",
                         "orientation_trust_max_error_deg",
                         "edge_confirmation_taps",
                         "belief_threshold",
                         "max_taps_per_decision",
                         "reposition_while_sensing",
                         "belief_evidence",
                         "completion_radius_mm",
                         "lost_outside_mm",
                         "lost_inside_mm",
                         "lost_plane_or_air_taps",
                         "tap_cap_perimeters",
                         "coverage_radius_mm",
                         "percept",
                         "percept_temperature",
                         "curvature_taps",
                         "same_edge_tolerance_deg",
                         "trials"});
    for (const FollowingNumber& n : followingNumbers())
        s.*n.member = f.number(n.key, n.lo, n.hi, s.*n.member);
    s.edgeConfirmationTaps = f.integer("edge_confirmation_taps", 1, 100, s.edgeConfirmationTaps);
    s.maxTapsPerDecision = f.integer("max_taps_per_decision", 1, 1000, s.maxTapsPerDecision);
    s.repositionWhileSensing = f.flag("reposition_while_sensing", s.repositionWhileSensing);
    if (f.has("belief_evidence")) {
        const std::string k = f.text("belief_evidence");
        if (k != "calibrated" && k != "naive_bayes")
            f.fail("belief_evidence",
                   "belief_evidence '" + k +
                       "' is neither calibrated (each tap scaled by the run's calibration) nor "
                       "naive_bayes (the log-likelihoods as they are)");
        s.calibratedBelief = k == "calibrated";
    }
    s.lostPlaneOrAirTaps = f.integer("lost_plane_or_air_taps", 1, 100000, s.lostPlaneOrAirTaps);
    if (f.has("percept")) {
        const std::string k = f.text("percept");
        const auto kind = perceptKindNamed(k);
        if (!kind)
            f.fail("percept", "percept '" + k +
                                  "' is neither discrete (the winning class, as the paper) nor "
                                  "continuous (angle and position from the whole posterior)");
        s.percept = *kind;
    }
    s.curvatureTaps = f.integer("curvature_taps", 0, 50, s.curvatureTaps);
    if (s.curvatureTaps == 1)
        f.fail("curvature_taps", "a turn needs two angles: give 0 (no anticipation) or 2 or more");
}

void parseFollowing(const JsonFields& f, ExperimentSpec& e, const std::string& baseDirectory) {
    parseFollowingSettings(f, e.following);
    if (!f.has("trials")) return;
    const Json& list = f.raw("trials");
    if (!list.is_array())
        f.fail("trials",
               "expected a list of trials, e.g. [{\"mode\": \"active\", \"object\": {\"shape\": "
               "\"cross\"}, \"repeats\": 2}]");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string place = f.placeOf("trials") + "/" + std::to_string(i);
        e.trials.push_back(
            parseTrial(JsonFields(list[i], f.source(), place), place, e, baseDirectory));
    }
}

/// The experiment's scene: inline, or the path of a scene file relative to the experiment.
SceneSpec parseSceneField(const JsonFields& f, const std::string& baseDirectory) {
    if (!f.has("scene"))
        f.fail("scene", "missing 'scene': a scene object or the path of a scene file");
    const Json& scene = f.raw("scene");
    if (scene.is_string()) {
        fs::path p(scene.get<std::string>());
        if (p.is_relative()) p = fs::path(baseDirectory) / p;
        std::error_code ec;
        if (!fs::exists(p, ec))
            f.fail("scene",
                   "scene file '" + shortened(p.string()) +
                       "' does not exist; check the path (relative to the experiment file)");
        return loadScene(p.string());
    } else {
        return parseScene(scene, f.source(), "/scene", baseDirectory);
    }
}

void parseClasses(const JsonFields& c, ClassSet& classes) {
    c.rejectUnknownKeys(
        {"orientations_deg", "orientation_step_deg", "positions", "position_step_mm"});
    if (c.has("orientations_deg") && c.has("orientation_step_deg"))
        c.fail("orientation_step_deg",
               "give either orientations_deg (a list) or orientation_step_deg (every so many "
               "degrees round the circle from 270), not both; a file that extends one with a "
               "list removes the list with \"orientations_deg\": null");
    if (c.has("orientation_step_deg")) {
        // Every `step` degrees round the circle, from the lower edge's 270.
        const double step = c.number("orientation_step_deg", 1.0, 180.0);
        const double count = 360.0 / step;
        if (std::abs(count - std::round(count)) > 1e-9)
            c.fail("orientation_step_deg",
                   numberText(step) +
                       " deg does not divide the circle into whole steps; use "
                       "a divisor of 360 such as 5, 10, 15 or 45");
        classes.orientationsDeg.clear();
        for (int i = 0; i < static_cast<int>(std::round(count)); ++i)
            classes.orientationsDeg.push_back(std::fmod(270.0 + i * step, 360.0));
    } else if (c.has("orientations_deg")) {
        classes.orientationsDeg = c.numbers("orientations_deg", -360.0, 360.0);
        const auto& o = classes.orientationsDeg;
        if (o.empty()) c.fail("orientations_deg", "list at least one orientation");
        if (o.size() > static_cast<std::size_t>(kMaxOrientations))
            c.fail("orientations_deg", std::to_string(o.size()) + " orientations; at most " +
                                           std::to_string(kMaxOrientations) + ", one per degree");
        // Two entries facing the same way would make classes no tap can tell apart.
        for (std::size_t i = 0; i < o.size(); ++i)
            for (std::size_t j = 0; j < i; ++j)
                if (angleDifferenceDeg(o[i], o[j]) < 1e-9)
                    c.fail("orientations_deg", "orientation " + numberText(o[i]) +
                                                   " deg faces the same way as orientation " +
                                                   numberText(o[j]) +
                                                   " deg before it; list each edge once");
    }
    classes.positions = c.integer("positions", 2, 200, classes.positions);
    classes.positionStep_mm = c.number("position_step_mm", 0.05, 10.0, classes.positionStep_mm);
}

void parseTraining(const JsonFields& t, TrainingProtocolSettings& training) {
    t.rejectUnknownKeys({"data_sets", "training_sets", "taps_per_class", "test_offset_mm",
                         "placement_jitter_mm", "retrain_on_all_sets"});
    training.dataSets = t.integer("data_sets", 2, 1000, training.dataSets);
    if (t.has("training_sets")) {
        training.trainingSets.clear();
        for (double s : t.numbers("training_sets", 1, 1000)) {
            if (s != std::floor(s))
                t.fail("training_sets", "data set " + numberText(s) +
                                            " is not a whole number; sets are numbered 1, 2, "
                                            "3 ...");
            training.trainingSets.push_back(static_cast<int>(s));
        }
    }
    training.tapsPerClass = t.integer("taps_per_class", 1, 1000, training.tapsPerClass);
    training.testOffset_mm = t.number("test_offset_mm", -5.0, 5.0, training.testOffset_mm);
    training.placementJitter_mm =
        t.number("placement_jitter_mm", 0.0, 5.0, training.placementJitter_mm);
    training.retrainOnAllSets = t.flag("retrain_on_all_sets", training.retrainOnAllSets);
    if (auto p = training.problem(); !p.empty()) throw InputError(t.source(), "/training", p);
}

void parseRecognition(const JsonFields& r, ExperimentSpec& e) {
    r.rejectUnknownKeys({"bins", "smoothing_sigma_bins", "of_mode"});
    e.recognition.enabled = true;
    e.recognition.bins = r.integer("bins", 2, 200, e.recognition.bins);
    e.recognition.smoothingSigmaBins =
        r.number("smoothing_sigma_bins", 0.0, 20.0, e.recognition.smoothingSigmaBins);
    e.recognition.ofMode = parseMode(r, "of_mode", "active");
    bool any = false;
    for (const auto& t : e.trials) any = any || t.mode == e.recognition.ofMode;
    if (!any)
        r.fail("of_mode", std::string("no ") + modeName(e.recognition.ofMode) +
                              " trials to recognise; add trials or change of_mode");
}

}  // namespace

ExperimentSpec parseExperiment(const Json& json, const std::string& source,
                               const std::string& baseDirectory) {
    JsonFields f(json, source, "");
    f.rejectUnknownKeys({"name", "description", "scene", "seed", "classes", "classifier",
                         "training", "validation", "following", "recognition", "sweeps"});
    ExperimentSpec e;
    e.source = source;
    e.name = f.text("name");
    e.description = f.text("description", "");
    e.scene = parseSceneField(f, baseDirectory);
    if (f.has("seed")) e.scene.seed = static_cast<std::uint64_t>(f.integer("seed", 0, 2147483647L));

    if (f.has("classes")) parseClasses(f.object("classes"), e.classes);
    if (f.has("classifier")) {
        const JsonFields c = f.object("classifier");
        c.rejectUnknownKeys({"bins", "smoothing", "kernel_sigma_bins"});
        e.classifier.bins = c.integer("bins", 1, 100000, e.classifier.bins);
        e.classifier.smoothing = c.number("smoothing", 1e-12, 1e6, e.classifier.smoothing);
        e.classifier.kernelSigma_bins =
            c.number("kernel_sigma_bins", 0.0, kMaxKernelSigma_bins, e.classifier.kernelSigma_bins);
    }
    if (f.has("training")) parseTraining(f.object("training"), e.training);
    if (f.has("validation")) {
        const JsonFields v = f.object("validation");
        v.rejectUnknownKeys({"valid_range_positions"});
        e.validRangeWidth =
            v.integer("valid_range_positions", 1, e.classes.positions, e.validRangeWidth);
    }
    if (f.has("following")) parseFollowing(f.object("following"), e, baseDirectory);
    if (f.has("recognition")) parseRecognition(f.object("recognition"), e);
    if (f.has("sweeps")) parseSweeps(f.object("sweeps"), e);
    if (const std::string problem = trainingObjectProblem(e); !problem.empty())
        throw InputError(source, "/scene", "training on the scene's object: " + problem);
    return e;
}

std::string trainingObjectProblem(const ExperimentSpec& e) {
    return trainingPosesProblem(e.scene.object.outline(), e.classes, e.training,
                                e.scene.stage.travel_mm);
}

std::vector<std::string> untrainedEdgeCautions(const ExperimentSpec& e, double toleranceDeg) {
    auto tenth = [](double v) { return numberText(std::round(v * 10.0) / 10.0); };
    std::string trained;
    for (double deg : e.classes.orientationsDeg)
        trained += (trained.empty() ? "" : ", ") + numberText(deg);
    std::vector<std::string> cautions;
    // A continuous percept does not snap to the trained orientations: it reads angles between
    // them from the posterior (docs/general-shapes.md), so there is nothing to caution about.
    if (e.following.percept == PerceptKind::Continuous) return cautions;
    for (const TrialSpec& t : e.trials) {
        const Polygon outline = t.object.outline();
        int off = 0;
        double worstDeg = 0.0;
        std::size_t worst = 0;
        double worstFacing = 0.0;
        for (std::size_t i = 0; i < outline.size(); ++i) {
            const Vec2 n = outline.outwardNormal(i);
            double facing = std::atan2(n.y, n.x) * 180.0 / M_PI;
            if (facing < 0.0) facing += 360.0;
            double nearest = 180.0;
            for (double deg : e.classes.orientationsDeg)
                nearest = std::min(nearest, angleDifferenceDeg(facing, deg));
            if (nearest <= toleranceDeg + 1e-9) continue;
            ++off;
            if (nearest > worstDeg + 1e-9) {  // ties: the first such edge
                worstDeg = nearest;
                worst = i;
                worstFacing = facing;
            }
        }
        if (off == 0) continue;
        const Vec2 a = outline.vertex(worst), b = outline.vertex(worst + 1);
        cautions.push_back(
            t.place + " (" + t.label + "): " + std::to_string(off) + " of " +
            std::to_string(outline.size()) + (off == 1 ? " edges faces" : " edges face") +
            " more than " + numberText(toleranceDeg) +
            " deg away from every trained orientation (" + trained + " deg); the worst, from (" +
            tenth(a.x) + ", " + tenth(a.y) + ") to (" + tenth(b.x) + ", " + tenth(b.y) +
            ") mm, faces " + tenth(worstFacing) + " deg, " + tenth(worstDeg) +
            " deg off. Every percept snaps the follow direction to a trained orientation, so "
            "following degrades along such edges; to follow them, list finer orientations in "
            "classes/orientations_deg and train on an object with an edge facing each");
    }
    return cautions;
}

namespace {

// Longer chains of "extends" are refused (docs/limits.md): real ones are two or three long.
constexpr std::size_t kMaxExtendsChain = 16;

// RFC 7386 merge patch: objects merge key by key, null removes a key, anything else replaces.
void mergePatch(Json& target, const Json& patch) {
    if (!patch.is_object() || !target.is_object()) {
        target = patch;
        return;
    }
    for (auto it = patch.begin(); it != patch.end(); ++it) {
        if (it.value().is_null())
            target.erase(it.key());
        else if (target.contains(it.key()))
            mergePatch(target[it.key()], it.value());
        else
            target[it.key()] = it.value();
    }
}

// The experiment at `path` with every "extends" resolved: the base experiment's document, with
// its scene path made absolute, patched by this one's keys. `chain` holds the files on the way,
// to refuse a circle.
Json resolvedExperiment(const std::string& path, std::vector<std::string>& chain) {
    // Paths come from files: one the system cannot even look up (too long, say) is not there.
    std::error_code ec;
    std::string canonical = fs::weakly_canonical(fs::path(path), ec).string();
    if (ec) canonical = fs::path(path).lexically_normal().string();
    if (std::find(chain.begin(), chain.end(), canonical) != chain.end()) {
        std::string circle;
        for (const auto& c : chain) circle += fs::path(c).filename().string() + " -> ";
        throw InputError(chain.back(), "/extends",
                         "experiments extend each other in a circle (" + circle +
                             fs::path(canonical).filename().string() +
                             "); let one of them name its settings instead");
    }
    if (chain.size() >= kMaxExtendsChain)
        throw InputError(chain.back(), "/extends",
                         "more than " + std::to_string(kMaxExtendsChain) +
                             " experiments extend one another in a chain; let one of them name "
                             "its settings instead of extending");
    Json j = readJsonFile(path);
    if (!looksLikeExperiment(j))
        throw InputError(path, "/",
                         "this is not an experiment file (it has neither 'scene' nor 'extends'); "
                         "give an experiment such as experiments/paper.json");
    const fs::path directory = fs::path(path).parent_path();
    if (j.contains("scene") && j["scene"].is_string()) {
        const fs::path scene(j["scene"].get<std::string>());
        if (scene.is_relative())
            j["scene"] = fs::absolute(directory / scene, ec).lexically_normal().string();
    }
    if (!j.contains("extends")) return j;
    const Json& extends = j["extends"];
    if (!extends.is_string() || extends.get<std::string>().empty())
        throw InputError(path, "/extends",
                         "expected the path of the experiment file this one builds on, e.g. "
                         "\"paper.json\"");
    fs::path basePath(extends.get<std::string>());
    if (basePath.is_relative()) basePath = directory / basePath;
    if (!fs::exists(basePath, ec))
        throw InputError(path, "/extends",
                         "the experiment it extends, '" + shortened(basePath.string()) +
                             "', does not exist; give its path relative to this file");
    chain.push_back(canonical);
    Json merged = resolvedExperiment(basePath.string(), chain);
    chain.pop_back();
    j.erase("extends");
    mergePatch(merged, j);
    return merged;
}

}  // namespace

Json readExperimentFile(const std::string& path) {
    std::vector<std::string> chain;
    return resolvedExperiment(path, chain);
}

ExperimentSpec loadExperiment(const std::string& path) {
    return parseExperiment(readExperimentFile(path), path, fs::path(path).parent_path().string());
}

}  // namespace activetouch
