#include <filesystem>

#include "core/common/NumberText.h"
#include "core/run/OutputFiles.h"
#include "core/run/RunArtefacts.h"
#include "core/run/RunFolder.h"
#include "core/run/SweepRecords.h"

namespace activetouch {
namespace fs = std::filesystem;

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

// summary.json's sections.

Json validationJson(const RunResult& r) {
    const ClassSet& cs = r.classes;
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
        if (v.continuousValidated)
            byClass.back()["continuous_angle_error_deg"] =
                e.continuousTaps > 0 ? Json(e.continuousAngleError_deg) : Json(nullptr);
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
    auto orNull = [](double x) { return x >= 0.0 ? Json(x) : Json(nullptr); };
    Json continuous = nullptr;
    if (v.continuousValidated)
        continuous = {
            {"median_angle_error_deg_in_valid_range",
             orNull(v.continuousMedianAngleErrorInRange_deg)},
            {"median_angle_error_deg", orNull(v.continuousMedianAngleError_deg)},
            {"along_paths",
             {{"median_angle_error_deg", orNull(r.pathMedianAngleError_deg)},
              {"taps", r.pathAngleTaps},
              {"which_taps",
               "following taps perceived as an edge with the tip inside the valid range and away "
               "from corners, against the outward normal of the outline nearest the tip"}}},
            {"temperature", r.spec.following.perceptTemperature > 0.0
                                ? Json(r.spec.following.perceptTemperature)
                                : Json("samples per taxel")}};
    return {{"continuous_percept", continuous},
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

Json followingJson(const RunResult& r) {
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
                             {"reachable", t.result.reachable},
                             {"coverage", t.result.coverage},
                             {"mean_contour_distance_mm", t.result.meanContourDistance_mm},
                             {"max_contour_distance_mm", t.result.maxContourDistance_mm},
                             {"progress_mm", t.result.progress_mm},
                             {"start_mm", {t.start.x, t.start.y}},
                             {"object_rotation_deg", t.rotationDeg},
                             {"furthest", placeJson(t.result)},
                             {"corners_rounded",
                              {{"convex", t.result.cornersRounded.convex},
                               {"concave", t.result.cornersRounded.concave}}}});
        if (t.recordedTaps >= 0) following.back()["recorded_taps"] = t.recordedTaps;
    }
    return following;
}

Json recognitionJson(const RunResult& r) {
    Json trials = Json::array();
    std::map<std::string, std::map<std::string, int>> confusion, confusionSmoothed,
        confusionAnyPose;
    for (const auto& t : r.trials) {
        if (!t.recognised) continue;
        trials.push_back({{"shape", t.label},
                          {"trial", t.trial},
                          {"predicted", t.recognition.predicted},
                          {"predicted_smoothed", t.recognition.predictedSmoothed},
                          {"distances", t.recognition.distances},
                          {"smoothed_distances", t.recognition.smoothedDistances}});
        if (t.poseRecognition.valid) {
            Json fits = Json::object();
            for (const PoseFit& f : t.poseRecognition.fits) fits[f.shape] = f.score_mm;
            const PoseFit& b = t.poseRecognition.best;
            trials.back()["any_pose"] = {
                {"predicted", t.poseRecognition.predicted},
                {"rotation_deg", b.symmetry == 0 ? Json(nullptr) : Json(b.rotationDeg)},
                {"symmetry", b.symmetry},
                {"position_mm", {b.position.x, b.position.y}},
                {"true_rotation_deg", t.rotationDeg},
                {"true_position_mm", {t.objectCentre.x, t.objectCentre.y}},
                {"position_is", "the centroid of the outline's length"},
                {"scores_mm", fits}};
            ++confusionAnyPose[t.label][t.poseRecognition.predicted];
        }
        ++confusion[t.label][t.recognition.predicted];
        ++confusionSmoothed[t.label][t.recognition.predictedSmoothed];
    }
    return {{"accuracy", r.recognitionAccuracy},
            {"accuracy_smoothed", r.recognitionAccuracySmoothed},
            {"of_mode", modeName(r.spec.recognition.ofMode)},
            {"bins", r.spec.recognition.bins},
            {"smoothing_sigma_bins", r.spec.recognition.smoothingSigmaBins},
            {"templates_pose",
             "each shape at the pose the experiment file states for it; where each trial draws "
             "its own turn, unturned (the shape's own frame): the rule is never handed a "
             "trial's turn"},
            {"trials", trials},
            {"confusion", confusion},
            {"confusion_smoothed", confusionSmoothed},
            {"any_pose",
             {{"accuracy", r.recognitionAccuracyAnyPose},
              {"median_rotation_error_deg", r.medianRotationError_deg},
              {"median_position_error_mm", r.medianPositionError_mm},
              {"confusion", confusionAnyPose},
              {"rule",
               "each shape's outline turned and moved onto the path, scored by the "
               "root mean square of distances both ways capped at 5 mm; the lowest "
               "score names the path"}}}};
}

Json sweepsJson(const SweepResults& sweeps) {
    Json perception = Json::array(), following = Json::array(), compute = Json::array();
    auto interval = [](const SweepEstimate& e) { return Json::array({e.low, e.high}); };
    auto perceptionRow = [&](const PerceptionSweepRow& row) {
        return Json{{"belief_threshold", row.threshold},
                    {"decisions", row.decisions},
                    {"mean_taps_per_decision", row.meanTaps},
                    {"mean_taps_per_decision_95ci", interval(row.taps)},
                    {"mean_robot_time_per_decision_s", row.meanRobotTime_s},
                    {"mean_robot_time_per_decision_s_95ci", interval(row.robotTime_s)},
                    {"edge_angle_error_deg", row.angleError_deg},
                    {"edge_angle_error_deg_95ci", interval(row.angle_deg)},
                    {"position_error_mm", row.positionError_mm},
                    {"position_error_mm_95ci", interval(row.position_mm)},
                    {"edge_angle_error_below_single_tap_deg", row.angleFall_deg.mean},
                    {"edge_angle_error_below_single_tap_deg_95ci", interval(row.angleFall_deg)},
                    {"position_error_below_single_tap_mm", row.positionFall_mm.mean},
                    {"position_error_below_single_tap_mm_95ci", interval(row.positionFall_mm)},
                    {"correct_fraction", row.correctFraction},
                    {"correct_fraction_95ci", interval(row.correct)},
                    {"plane_decisions", row.planeDecisions},
                    {"plane_perceived_as_plane", row.planeRecognised},
                    {"air_decisions", row.airDecisions},
                    {"air_perceived_as_air", row.airRecognised}};
    };
    for (const auto& row : sweeps.perception) perception.push_back(perceptionRow(row));
    for (const auto& row : sweeps.following)
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
    for (const auto& row : sweeps.compute)
        compute.push_back({{"bins", row.bins},
                           {"samples_per_tap", row.samples},
                           {"angle_error_deg", row.angleError_deg},
                           {"position_error_mm", row.positionError_mm},
                           {"microseconds_per_decision", row.microsecondsPerDecision},
                           {"paper_setting", row.paperSetting}});
    Json out = {{"perception", perception}, {"following", following}, {"compute", compute}};
    if (sweeps.bandit.ran) out["bandit"] = banditJson(sweeps.bandit, sweeps.following);
    if (!sweeps.robustness.empty()) out["robustness"] = robustnessJson(sweeps);
    if (!sweeps.perception.empty()) {
        Json single = perceptionRow(sweeps.perceptionSingleTap);
        single.erase("belief_threshold");
        single["what"] =
            "the paper's operating point on the same taps: one tap, its most likely class";
        out["perception_single_tap"] = single;
    }
    if (const PerceptionSweepCalibration& c = sweeps.perceptionCalibration; c.measured)
        out["perception_calibration"] = {
            {"taps", c.taps},
            {"belief", c.calibrated ? "calibrated (the run's belief_calibration scaling)"
                                    : "naive Bayes (no calibration measured)"},
            {"ece_raw", c.eceRaw},
            {"ece_calibrated", c.eceCalibrated},
            {"ece_if_perfectly_calibrated", c.eceIfCalibrated},
            {"which_taps",
             "the sweep's fresh taps: used neither to train the classifier nor to fit the "
             "calibration"}};
    return out;
}

/// The belief's calibration on the held-out taps: every candidate factor, the one chosen, and
/// the reliability of the raw and calibrated beliefs.
Json beliefCalibrationJson(const BeliefCalibration& b) {
    auto bins = [](const std::vector<ReliabilityBin>& v) {
        Json a = Json::array();
        for (const ReliabilityBin& x : v)
            a.push_back({{"confidence_from", x.lo},
                         {"confidence_to", x.hi},
                         {"taps", x.taps},
                         {"mean_confidence", x.meanConfidence},
                         {"accuracy", x.accuracy}});
        return a;
    };
    return {
        {"ece_raw", b.eceRaw},
        {"ece_calibrated", b.eceCalibrated},
        {"ece_if_perfectly_calibrated", b.eceIfCalibrated},
        {"scaling",
         {{"method", b.method}, {"factor", b.scaling.scale}, {"floor", b.scaling.floor}}},
        {"sequential",
         {{"factor", b.sequential.scale},
          {"running_sums_fitted", b.sequencePrefixes},
          {"what",
           "the factor on evidence accumulated over repeated taps (sequential decisions), "
           "fitted on the running sums of each class's held-out taps"}}},
        {"candidates",
         {{"fitted_temperature", {{"factor", b.fittedScale}, {"ece", b.eceFitted}}},
          {"fitted_temperature_and_floor",
           {{"factor", b.fittedWithFloor.scale},
            {"floor", b.fittedWithFloor.floor},
            {"ece", b.eceFittedWithFloor}}},
          {"mean_per_sample", {{"factor", b.perSampleScale}, {"ece", b.ecePerSample}}}}},
        {"single_tap_accuracy", b.accuracy},
        {"taps_fitted", b.fitTaps},
        {"taps_evaluated", b.evaluationTaps},
        {"which_taps",
         "the held-out (test) taps: the factor fitted on every other one, every error "
         "measured on the rest"},
        {"reliability", {{"raw", bins(b.raw)}, {"calibrated", bins(b.calibrated)}}}};
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
    if (!r.validation.byClass.empty()) j["validation"] = validationJson(r);
    if (r.beliefCalibration.measured)
        j["belief_calibration"] = beliefCalibrationJson(r.beliefCalibration);
    if (!r.failure.empty()) j["failure"] = r.failure;
    j["cautions"] = untrainedEdgeCautions(r.spec);
    j["controller"] = {
        {"valid_offsets_mm", {r.validOffsets.low, r.validOffsets.high}},
        {"orientation_trusted_positions", {r.trustedPositions.first, r.trustedPositions.second}},
        {"orientation_trusted_offsets_mm", {r.validOffsets.trustedLow, r.validOffsets.trustedHigh}},
        {"orientation_trust_max_error_deg", r.spec.following.orientationTrustMaxError_deg}};
    j["following"] = followingJson(r);
    if (!r.templates.empty()) j["recognition"] = recognitionJson(r);
    if (!r.sweeps.empty()) j["sweeps"] = sweepsJson(r.sweeps);
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

ArtefactTiming writeRunArtefacts(const RunResult& result, const std::string& outDir,
                                 std::chrono::steady_clock::time_point started,
                                 const std::function<double()>& drawFigures) {
    writeRunTables(result, outDir);
    ArtefactTiming t;
    if (drawFigures) t.figures_s = drawFigures();
    t.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    writeSummary(result, outDir, t.wall_s, t.figures_s);
    return t;
}

}  // namespace activetouch
