// Sweeps over seeds as rates.json's sweeps section, as the sweeps_*.csv tables and as the text a
// terminal shows (docs/accuracy-vs-time.md).
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <string_view>

#include "core/analysis/SweepRates.h"
#include "core/run/OutputFiles.h"
#include "core/run/SweepRecords.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {

std::string estimateText(const SweepEstimate& e, const char* format) {
    // No value is a dash, never a NaN or an infinity (the report's note says when).
    if (!std::isfinite(e.mean)) return "-";
    char buf[96];
    if (!std::isfinite(e.low) || !std::isfinite(e.high)) {
        std::snprintf(buf, sizeof buf, format, e.mean);
        return std::string(buf) + " (-)";
    }
    const std::string f = std::string(format) + " (" + format + " to " + format + ")";
    std::snprintf(buf, sizeof buf, f.c_str(), e.mean, e.low, e.high);
    return buf;
}

Json intervalJson(const SweepEstimate& e) {
    auto finite = [](double v) { return std::isfinite(v) ? Json(v) : Json(); };
    return Json::array({finite(e.low), finite(e.high)});
}

Json estimateJson(const SweepEstimate& e) {
    return {{"mean", std::isfinite(e.mean) ? Json(e.mean) : Json()}, {"ci95", intervalJson(e)}};
}

Json perceptionJson(const PerceptionOverSeeds& p) {
    return {{"belief_threshold", p.threshold},
            {"seeds", p.seeds},
            {"mean_taps_per_decision", estimateJson(p.taps)},
            {"mean_robot_time_per_decision_s", estimateJson(p.robotTime_s)},
            {"edge_angle_error_deg", estimateJson(p.angle_deg)},
            {"position_error_mm", estimateJson(p.position_mm)},
            {"correct_fraction", estimateJson(p.correct)},
            {"edge_angle_error_below_single_tap_deg", estimateJson(p.angleFall_deg)},
            {"position_error_below_single_tap_mm", estimateJson(p.positionFall_mm)},
            {"plane_perceived_as_plane", estimateJson(p.planeRecognised)},
            {"air_perceived_as_air", estimateJson(p.airRecognised)}};
}

}  // namespace

namespace {

/// One setting of sweep (b) over seeds, with its pairing against the paper's setting.
Json followingJson(const FollowingOverSeeds& f) {
    Json row = {{"mode", modeName(f.mode)},
                {"follow_step_mm", f.followStep_mm},
                {"reposition_step_mm", f.repositionStep_mm},
                {"belief_threshold", f.beliefThreshold},
                {"paper_setting", f.paperSetting},
                {"seeds", f.seeds},
                {"completed", rateJson(f.completed)},
                {"mean_contour_distance_mm", estimateJson(f.contourDistance_mm)},
                {"mean_robot_time_per_trial_s", estimateJson(f.robotTimePerTrial_s)},
                {"mean_taps_per_trial", estimateJson(f.tapsPerTrial)},
                {"robot_time_per_completion_s", estimateJson(f.robotTimePerCompletion_s)},
                {"on_pareto_front", f.onParetoFront}};
    if (f.paired)
        row["against_paper_setting"] = {
            {"completion_difference_points", estimateJson(f.completionDifference_points)},
            {"robot_time_per_completion_ratio", estimateJson(f.timeRatio)},
            {"contour_distance_difference_mm", estimateJson(f.distanceDifference_mm)},
            {"beats_paper", f.beatsPaper},
            {"paired_seeds", f.pairedSeeds},
            {"verdict", f.verdict == PaperVerdict::Beats         ? "beats"
                        : f.verdict == PaperVerdict::DoesNotBeat ? "does not beat"
                                                                 : "not enough seeds yet"}};
    return row;
}

}  // namespace

Json sweepRatesJson(const SweepRates& r) {
    Json perception = Json::array(), following = Json::array(), compute = Json::array();
    for (const auto& p : r.perception) perception.push_back(perceptionJson(p));
    for (const auto& f : r.following) following.push_back(followingJson(f));
    for (const auto& c : r.compute)
        compute.push_back({{"bins", c.bins},
                           {"samples_per_tap", c.samples},
                           {"paper_setting", c.paperSetting},
                           {"angle_error_deg", estimateJson(c.angle_deg)},
                           {"position_error_mm", estimateJson(c.position_mm)},
                           {"microseconds_per_decision", estimateJson(c.microsecondsPerDecision)}});
    Json out = {{"seeds", r.seeds},
                {"intervals",
                 "95 %: Student's t over the seeds' means; completion by Wilson over trials; robot "
                 "time per completion and its ratio to the paper's setting by resampling the seeds "
                 "(2000 draws, a fixed generator)"},
                {"perception", perception},
                {"following", following},
                {"compute", compute}};
    if (!r.perception.empty()) out["perception_single_tap"] = perceptionJson(r.perceptionSingleTap);
    if (r.calibrationSeeds > 0)
        out["perception_calibration"] = {
            {"seeds", r.calibrationSeeds},
            {"seeds_with_ece_calibrated_at_most_0.05", r.calibrationWithin005},
            {"ece_raw", estimateJson(r.eceRaw)},
            {"ece_calibrated", estimateJson(r.eceCalibrated)},
            {"ece_if_perfectly_calibrated", estimateJson(r.eceIfCalibrated)}};
    if (!r.robustness.empty()) {
        Json rows = Json::array();
        const std::vector<RobustnessOverSeeds> all = firstThen(r.robustnessBase, r.robustness);
        for (const auto& f : all)
            rows.push_back(
                {{"fault", f.fault},
                 {"seeds", f.seeds},
                 {"failed_runs", f.failedRuns},
                 {"active_completed", rateJson(f.completed)},
                 {"recognised_paper_rule", rateJson(f.recognisedRaw)},
                 {"recognised_any_pose", rateJson(f.recognisedAnyPose)},
                 {"completion_fall_points", estimateJson(f.completionFall_points)},
                 {"recognised_of_trials_fall_points", estimateJson(f.recognitionFall_points)},
                 {"validation_angle_error_deg", estimateJson(f.angleError_deg)}});
        out["robustness"] = rows;
    }
    if (const BanditOverSeeds& b = r.bandit; b.seeds > 0) {
        Json choices = Json::array();
        for (const auto& [row, count] : b.choices)
            choices.push_back({{"setting", settingName(r.following[std::size_t(row)])},
                               {"sweep_row", row},
                               {"seeds", count}});
        out["bandit"] = {
            {"seeds", b.seeds},
            {"completion_worth_s", b.completionWorth_s},
            {"chose_the_seeds_best", b.choseBest},
            {"regret_per_trial", estimateJson(b.regret)},
            {"regret_against_best_over_seeds", estimateJson(b.pooledRegret)},
            {"best_over_seeds", b.pooledBest >= 0
                                    ? Json(settingName(r.following[std::size_t(b.pooledBest)]))
                                    : Json()},
            {"robot_time_s", b.robotTime_s},
            {"sweep_robot_time_s", b.sweepRobotTime_s},
            {"choices", choices}};
    }
    if (!r.following.empty())
        out["beats_paper_rule"] =
            "robot time per completion below the paper's setting (upper end of the 95 % interval "
            "of the ratio under 1) and completion no lower (lower end of the paired difference "
            "above -" +
            std::to_string(int(kCompletionMargin_points)) + " percentage points)";
    return out;
}

namespace {

/// Prints `format` into `file` as print does, but with every field that came out as a
/// non-finite number ("nan", "-nan", "inf", "-inf") left empty: a table holds no value there,
/// never a NaN (docs/accuracy-vs-time.md says when a value is missing).
void cells(OutputFile& file, const char* format, ...) {
    char buf[2048];
    va_list args;
    va_start(args, format);
    std::vsnprintf(buf, sizeof buf, format, args);
    va_end(args);
    std::string out;
    std::string_view text(buf);
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find_first_of(",\n", start);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view field = text.substr(start, end - start);
        if (field != "nan" && field != "-nan" && field != "inf" && field != "-inf") out += field;
        if (end < text.size()) out += text[end];
        start = end + 1;
    }
    file.print("%s", out.c_str());
}

}  // namespace

namespace {

/// sweeps_perception.csv: sweep (a) over seeds.
void writePerceptionTable(const SweepRates& r, const std::string& dir) {
    auto finite = [](double v) { return std::isfinite(v) ? v : std::nan(""); };
    OutputFile f((fs::path(dir) / "sweeps_perception.csv").string());
    cells(f,
          "belief_threshold,seeds,mean_taps,mean_taps_lo,mean_taps_hi,robot_time_s,"
          "robot_time_s_lo,robot_time_s_hi,edge_angle_error_deg,edge_angle_error_deg_lo,"
          "edge_angle_error_deg_hi,position_error_mm,position_error_mm_lo,position_error_mm_hi,"
          "correct_fraction,correct_fraction_lo,correct_fraction_hi,angle_fall_deg,"
          "angle_fall_deg_lo,angle_fall_deg_hi,position_fall_mm,position_fall_mm_lo,"
          "position_fall_mm_hi,plane_as_plane,air_as_air\n");
    const std::vector<PerceptionOverSeeds> rows = firstThen(r.perceptionSingleTap, r.perception);
    for (const auto& p : rows) {
        if (p.threshold == 0)
            cells(f, "single_tap,%d", p.seeds);
        else
            cells(f, "%g,%d", p.threshold, p.seeds);
        for (const SweepEstimate* e : {&p.taps, &p.robotTime_s, &p.angle_deg, &p.position_mm,
                                       &p.correct, &p.angleFall_deg, &p.positionFall_mm})
            cells(f, ",%.5g,%.5g,%.5g", e->mean, finite(e->low), finite(e->high));
        cells(f, ",%.4f,%.4f\n", p.planeRecognised.mean, p.airRecognised.mean);
    }
    f.close();
}

/// sweeps_following.csv: sweep (b) over seeds.
void writeFollowingTable(const SweepRates& r, const std::string& dir) {
    auto finite = [](double v) { return std::isfinite(v) ? v : std::nan(""); };
    OutputFile f((fs::path(dir) / "sweeps_following.csv").string());
    cells(f,
          "mode,follow_step_mm,reposition_step_mm,belief_threshold,paper_setting,seeds,trials,"
          "completed,completed_rate,completed_lo,completed_hi,contour_distance_mm,"
          "contour_distance_mm_lo,contour_distance_mm_hi,robot_time_per_trial_s,taps_per_trial,"
          "robot_time_per_completion_s,robot_time_per_completion_s_lo,"
          "robot_time_per_completion_s_hi,completion_vs_paper_points,"
          "completion_vs_paper_points_lo,completion_vs_paper_points_hi,time_ratio_vs_paper,"
          "time_ratio_vs_paper_lo,time_ratio_vs_paper_hi,on_pareto_front,beats_paper\n");
    for (const auto& s : r.following) {
        cells(f, "%s,%g,%g,%g,%d,%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.2f,%.3f,%.3f,%.3f",
              modeName(s.mode), s.followStep_mm, s.repositionStep_mm, s.beliefThreshold,
              int(s.paperSetting), s.seeds, s.completed.total, s.completed.count,
              s.completed.fraction(), s.completed.low(), s.completed.high(),
              s.contourDistance_mm.mean, s.contourDistance_mm.low, s.contourDistance_mm.high,
              s.robotTimePerTrial_s.mean, s.tapsPerTrial.mean,
              finite(s.robotTimePerCompletion_s.mean), finite(s.robotTimePerCompletion_s.low),
              finite(s.robotTimePerCompletion_s.high));
        if (s.paired)
            cells(f, ",%.3f,%.3f,%.3f,%.4f,%.4f,%.4f", s.completionDifference_points.mean,
                  finite(s.completionDifference_points.low),
                  finite(s.completionDifference_points.high), finite(s.timeRatio.mean),
                  finite(s.timeRatio.low), finite(s.timeRatio.high));
        else
            cells(f, ",,,,,,");
        cells(f, ",%d,%d\n", int(s.onParetoFront), int(s.beatsPaper));
    }
    f.close();
}

/// sweeps_robustness.csv: sweep (e) over seeds.
void writeRobustnessTable(const SweepRates& r, const std::string& dir) {
    auto finite = [](double v) { return std::isfinite(v) ? v : std::nan(""); };
    OutputFile f((fs::path(dir) / "sweeps_robustness.csv").string());
    cells(f,
          "fault,seeds,failed_runs,active_trials,active_completed,completed_rate,completed_lo,"
          "completed_hi,completion_fall_points,completion_fall_points_lo,"
          "completion_fall_points_hi,recognition_trials,recognised_raw,recognised_rate,"
          "recognised_lo,recognised_hi,recognised_any_pose,recognition_fall_points,"
          "recognition_fall_points_lo,recognition_fall_points_hi,validation_angle_error_deg\n");
    const std::vector<RobustnessOverSeeds> all = firstThen(r.robustnessBase, r.robustness);
    for (const auto& x : all)
        cells(f,
              "%s,%d,%d,%d,%d,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f,%d,%d,%.4f,%.4f,%.4f,%d,%.3f,%.3f,"
              "%.3f,%.3f\n",
              csvField({x.fault}).c_str(), x.seeds, x.failedRuns, x.completed.total,
              x.completed.count, x.completed.fraction(), x.completed.low(), x.completed.high(),
              x.completionFall_points.mean, finite(x.completionFall_points.low),
              finite(x.completionFall_points.high), x.recognisedRaw.total, x.recognisedRaw.count,
              x.recognisedRaw.fraction(), x.recognisedRaw.low(), x.recognisedRaw.high(),
              x.recognisedAnyPose.count, x.recognitionFall_points.mean,
              finite(x.recognitionFall_points.low), finite(x.recognitionFall_points.high),
              x.angleError_deg.mean);
    f.close();
}

/// sweeps_compute.csv: sweep (c) over seeds.
void writeComputeTable(const SweepRates& r, const std::string& dir) {
    auto finite = [](double v) { return std::isfinite(v) ? v : std::nan(""); };
    OutputFile f((fs::path(dir) / "sweeps_compute.csv").string());
    cells(f,
          "bins,samples_per_tap,paper_setting,angle_error_deg,angle_error_deg_lo,"
          "angle_error_deg_hi,position_error_mm,position_error_mm_lo,position_error_mm_hi,"
          "microseconds_per_decision\n");
    for (const auto& c : r.compute)
        cells(f, "%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f\n", c.bins, c.samples,
              int(c.paperSetting), c.angle_deg.mean, finite(c.angle_deg.low),
              finite(c.angle_deg.high), c.position_mm.mean, finite(c.position_mm.low),
              finite(c.position_mm.high), c.microsecondsPerDecision.mean);
    f.close();
}

}  // namespace

void writeSweepRateTables(const SweepRates& r, const std::string& dir) {
    if (!r.perception.empty()) writePerceptionTable(r, dir);
    if (!r.following.empty()) writeFollowingTable(r, dir);
    if (!r.robustness.empty()) writeRobustnessTable(r, dir);
    if (!r.compute.empty()) writeComputeTable(r, dir);
}

namespace {

/// Sweep (a) over seeds, for a terminal.
void describePerception(const SweepRates& r, std::vector<std::string>& lines) {
    char buf[512];
    lines.push_back("  (a) sequential perception");
    lines.push_back(
        "    threshold   taps per decision     edge angle error (deg)   position error (mm)   "
        "angle fall (deg)      position fall (mm)");
    const std::vector<PerceptionOverSeeds> rows = firstThen(r.perceptionSingleTap, r.perception);
    for (const auto& p : rows) {
        std::snprintf(
            buf, sizeof buf, "    %-10s  %-20s  %-23s  %-20s  %-20s  %s",
            p.threshold == 0 ? "single tap" : thresholdName(p.threshold).substr(10).c_str(),
            estimateText(p.taps, "%.2f").c_str(), estimateText(p.angle_deg, "%.1f").c_str(),
            estimateText(p.position_mm, "%.2f").c_str(),
            p.threshold == 0 ? "" : estimateText(p.angleFall_deg, "%.1f").c_str(),
            p.threshold == 0 ? "" : estimateText(p.positionFall_mm, "%.2f").c_str());
        lines.push_back(buf);
    }
}

/// Sweep (b) over seeds, for a terminal.
void describeFollowing(const SweepRates& r, std::vector<std::string>& lines) {
    char buf[512];
    lines.push_back("  (b) contour following (time: robot seconds per completed trial)");
    lines.push_back(
        "    setting                          completed               distance (mm)          "
        "time per completion (s)   vs paper: completion (points)  time ratio");
    for (const auto& f : r.following) {
        char completed[64];
        std::snprintf(completed, sizeof completed, "%5.1f %% (%.1f to %.1f)",
                      100 * f.completed.fraction(), 100 * f.completed.low(),
                      100 * f.completed.high());
        std::string mark = f.paperSetting ? " paper" : "";
        if (f.onParetoFront) mark += " front";
        if (f.verdict == PaperVerdict::Beats) mark += " BEATS";
        std::snprintf(
            buf, sizeof buf, "    %-32s %-23s %-22s %-25s %-30s %-20s%s", settingName(f).c_str(),
            completed, estimateText(f.contourDistance_mm, "%.2f").c_str(),
            std::isfinite(f.robotTimePerCompletion_s.mean)
                ? estimateText(f.robotTimePerCompletion_s, "%.1f").c_str()
                : "none completed",
            f.paired ? estimateText(f.completionDifference_points, "%+.1f").c_str() : "",
            f.paired && std::isfinite(f.timeRatio.mean) ? estimateText(f.timeRatio, "%.2f").c_str()
                                                        : "",
            mark.c_str());
        lines.push_back(buf);
    }
    std::string beating, undecided;
    for (const auto& f : r.following) {
        if (f.verdict == PaperVerdict::Beats)
            beating += (beating.empty() ? "" : "; ") + settingName(f);
        if (f.paired && f.verdict == PaperVerdict::NotEnoughSeeds)
            undecided += (undecided.empty() ? "" : "; ") + settingName(f) + " (" +
                         std::to_string(f.pairedSeeds) + " paired seeds)";
    }
    lines.push_back("    beat the paper's setting in robot time at no loss of completion: " +
                    (beating.empty() ? std::string("none") : beating));
    if (!undecided.empty())
        lines.push_back("    not enough seeds yet for a verdict on: " + undecided +
                        "; a verdict needs " + std::to_string(kMinVerdictSeeds) +
                        " paired seeds and intervals of non-zero width");
    lines.push_back(
        "    (a dash: no value; no trial of that setting completed, or no seed "
        "had such decisions)");
}

/// Sweep (e) over seeds, for a terminal.
void describeRobustnessOverSeeds(const SweepRates& r, std::vector<std::string>& lines) {
    char buf[512];
    lines.push_back(
        "  (e) robustness: the whole run again with one fault (falls: below the fault-free "
        "run of the same seed, percentage points)");
    lines.push_back(
        "    fault               active completed          completion fall        "
        "recognised (paper's rule)   recognised-of-trials fall");
    const std::vector<RobustnessOverSeeds> all = firstThen(r.robustnessBase, r.robustness);
    for (const auto& f : all) {
        char completed[64], recognised[64];
        std::snprintf(completed, sizeof completed, "%5.1f %% (%.1f to %.1f)",
                      100 * f.completed.fraction(), 100 * f.completed.low(),
                      100 * f.completed.high());
        std::snprintf(recognised, sizeof recognised, "%5.1f %% (%.1f to %.1f)",
                      100 * f.recognisedRaw.fraction(), 100 * f.recognisedRaw.low(),
                      100 * f.recognisedRaw.high());
        const bool base = f.fault == "none";
        const std::string failed =
            f.failedRuns ? " (" + std::to_string(f.failedRuns) + " runs failed)" : "";
        std::snprintf(
            buf, sizeof buf, "    %-19s %-25s %-22s %-27s %s%s",
            base ? "none (base)" : f.fault.c_str(), completed,
            base ? "" : estimateText(f.completionFall_points, "%+.1f").c_str(), recognised,
            base ? "" : estimateText(f.recognitionFall_points, "%+.1f").c_str(), failed.c_str());
        lines.push_back(buf);
    }
}

/// Sweep (c) over seeds, for a terminal.
void describeCompute(const SweepRates& r, std::vector<std::string>& lines) {
    char buf[512];
    lines.push_back("  (c) compute");
    for (const auto& c : r.compute) {
        std::snprintf(buf, sizeof buf,
                      "    %3d bins x %2d samples: angle %s deg, position %s mm, %.2f us per "
                      "decision%s",
                      c.bins, c.samples, estimateText(c.angle_deg, "%.1f").c_str(),
                      estimateText(c.position_mm, "%.2f").c_str(), c.microsecondsPerDecision.mean,
                      c.paperSetting ? "  (paper)" : "");
        lines.push_back(buf);
    }
}

}  // namespace

std::vector<std::string> describeSweepRates(const SweepRates& r) {
    std::vector<std::string> lines;
    if (r.empty()) return lines;
    char buf[512];
    std::snprintf(
        buf, sizeof buf,
        "accuracy-versus-time sweeps over %d seeds (means over seeds, 95 %% intervals):", r.seeds);
    lines.push_back(buf);
    if (r.calibrationSeeds > 0) {
        std::snprintf(buf, sizeof buf,
                      "  one tap's belief, expected calibration error: raw %s, calibrated %s "
                      "(perfectly calibrated would show %s); calibrated <= 0.05 in %d of %d seeds",
                      estimateText(r.eceRaw, "%.3f").c_str(),
                      estimateText(r.eceCalibrated, "%.3f").c_str(),
                      estimateText(r.eceIfCalibrated, "%.3f").c_str(), r.calibrationWithin005,
                      r.calibrationSeeds);
        lines.push_back(buf);
    }
    if (!r.perception.empty()) describePerception(r, lines);
    if (!r.following.empty()) describeFollowing(r, lines);
    if (!r.robustness.empty()) describeRobustnessOverSeeds(r, lines);
    if (const BanditOverSeeds& b = r.bandit; b.seeds > 0) {
        std::snprintf(
            buf, sizeof buf,
            "  (d) bandit (reward: completion less robot time / %g s): chose its seed's "
            "best setting in %d of %d seeds; regret per trial %s against the seed's "
            "best, %s against the best over seeds (%s); robot time %.0f%% of sweep "
            "(b)'s active settings",
            b.completionWorth_s, b.choseBest, b.seeds, estimateText(b.regret, "%.3f").c_str(),
            estimateText(b.pooledRegret, "%.3f").c_str(),
            b.pooledBest >= 0 ? settingName(r.following[std::size_t(b.pooledBest)]).c_str()
                              : "none",
            b.sweepRobotTime_s > 0 ? 100.0 * b.robotTime_s / b.sweepRobotTime_s : 0.0);
        lines.push_back(buf);
        std::string most = "    chosen most often:";
        for (std::size_t i = 0; i < b.choices.size() && i < 4; ++i)
            most += (i ? "; " : " ") + settingName(r.following[std::size_t(b.choices[i].first)]) +
                    " (" + std::to_string(b.choices[i].second) + ")";
        lines.push_back(most);
    }
    if (!r.compute.empty()) describeCompute(r, lines);
    return lines;
}

}  // namespace activetouch
