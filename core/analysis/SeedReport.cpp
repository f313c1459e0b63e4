#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>

#include "core/analysis/SeedRates.h"
#include "core/analysis/SweepRates.h"
#include "core/run/OutputFiles.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {

Json shortJson(const ShortOfPaper& s) {
    return {{"runs", s.runs},
            {"passive_trial_not_lost_at_a_corner", s.passiveNotLost},
            {"active_trial_lost", s.activeLost},
            {"path_misnamed_paper_rule", s.misnamedRaw}};
}

Json tracingJson(const Tracing& t) {
    return {{"trials", t.trials},
            {"coverage_mean", t.trials > 0 ? Json(t.coverage()) : Json(nullptr)},
            {"mean_contour_distance_mm_mean",
             t.trials > 0 ? Json(t.meanDistance_mm()) : Json(nullptr)}};
}
Json byValidRange(const SeedRates& r) {
    Json list = Json::array();
    for (const ValidRangeRate& v : r.activeCompletedByValidRange()) {
        Json j = rateJson(v.activeCompleted);
        j["valid_range_positions"] = {v.range.first, v.range.last};
        j["runs"] = v.runs;
        list.push_back(j);
    }
    return list;
}
Json cornersJson(const CornerTally& t) {
    return {{"not_completed_got_furthest_near",
             {{"convex_corner", t.endedConvex},
              {"concave_corner", t.endedConcave},
              {"away_from_corners", t.endedAway}}},
            {"convex_corners_rounded", rateJson(t.convexRounded())},
            {"concave_corners_rounded", rateJson(t.concaveRounded())}};
}

}  // namespace

static Json seedRatesCoreJson(const SeedRates& r) {
    Json seeds = Json::array();
    for (const auto& s : r.seeds)
        seeds.push_back(
            {{"seed", s.seed},
             {"passive_trials", s.passiveTrials},
             {"passive_lost", s.passiveLost},
             {"passive_lost_at_a_corner", s.passiveLostAtCorner()},
             {"active_trials", s.activeTrials},
             {"active_completed", s.activeCompleted},
             {"recognition_trials", s.recognitionTrials()},
             {"recognised_raw", s.recognisedRaw()},
             {"recognised_smoothed", s.recognisedSmoothed()},
             {"recognised_any_pose", s.recognisedAnyPose()},
             {"validation_angle_error_deg", s.angleError_deg},
             {"validation_position_error_mm", s.positionError_mm},
             {"valid_range_positions", {s.validRange.first, s.validRange.last}},
             {"run_robot_time_s", s.runRobotTime_s},
             {"paper_result", s.paperResultApplies() ? Json(s.paperResult()) : Json(nullptr)},
             {"paper_result_smoothed",
              s.paperResultApplies() ? Json(s.paperResultSmoothed()) : Json(nullptr)},
             {"active_failures", s.failures},
             {"passive_not_lost_at_a_corner", s.passiveShortfalls},
             {"misnamed_paths", s.misnamed()},
             {"run_failure", s.failed() ? Json(s.runFailure) : Json(nullptr)},
             {"trials_not_run", s.trialsNotRun}});
    auto byLabel = [](const RatesByLabel& rates) {
        Json list = Json::array();
        for (const auto& [label, rate] : rates) {
            Json entry = rateJson(rate);
            entry["label"] = label;
            list.push_back(entry);
        }
        return list;
    };
    const RecognitionConfusion confusion = r.confusion();
    return {{"seeds", seeds},
            {"runs", r.seeds.size()},
            {"runs_failed", rateJson(r.runsFailed())},
            {"passive_lost", rateJson(r.passiveLost())},
            {"passive_lost_by_label", byLabel(r.passiveLostByLabel())},
            {"passive_lost_at_a_corner", rateJson(r.passiveLostAtCorner())},
            {"active_completed", rateJson(r.activeCompleted())},
            {"active_completed_by_label", byLabel(r.activeCompletedByLabel())},
            {"active_completed_by_valid_range", byValidRange(r)},
            {"recognised_raw", rateJson(r.recognisedRaw())},
            {"recognised_raw_by_trial", byLabel(r.recognisedRawByTrial())},
            {"recognised_smoothed", rateJson(r.recognisedSmoothed())},
            {"recognised_any_pose", rateJson(r.recognisedAnyPose())},
            {"any_pose_median_turn_error_deg",
             r.medianTurnError_deg() >= 0 ? Json(r.medianTurnError_deg()) : Json(nullptr)},
            {"any_pose_median_place_error_mm",
             r.medianPlaceError_mm() >= 0 ? Json(r.medianPlaceError_mm()) : Json(nullptr)},
            {"recognition_confusion",
             {{"labels", confusion.labels},
              {"rows", "traced shape"},
              {"columns", "named as"},
              {"paper_rule", confusion.raw},
              {"smoothed", confusion.smoothed},
              {"any_pose", confusion.anyPose}}},
            {"paper_result", rateJson(r.paperResult())},
            {"paper_result_smoothed", rateJson(r.paperResultSmoothed())},
            {"paper_result_short_by", shortJson(r.shortOfPaper())},
            {"taps_per_completed_trial", r.tapsPerCompletedTrial()},
            {"robot_time_per_completed_trial_s", r.robotTimePerCompletedTrial_s()},
            {"robot_time_per_run_s", r.robotTimePerRun_s()},
            {"corners",
             {{"active", cornersJson(r.corners(FollowingMode::Active))},
              {"passive", cornersJson(r.corners(FollowingMode::Passive))},
              {"near",
               "the furthest point along the contour within half the classes' window of "
               "a corner"}}},
            {"completed_tracing",
             {{"active", tracingJson(r.tracing(FollowingMode::Active))},
              {"passive", tracingJson(r.tracing(FollowingMode::Passive))}}},
            {"intervals", "Wilson score, 95 %"}};
}

Json seedRatesJson(const SeedRates& r) {
    Json out = seedRatesCoreJson(r);
    if (const SweepRates sweeps = sweepRates(r.seeds); !sweeps.empty())
        out["sweeps"] = sweepRatesJson(sweeps);
    return out;
}

void writeSeedRatesFiles(const SeedRates& rates, const std::string& outDir) {
    writeJsonAtomically((fs::path(outDir) / "rates.json").string(), seedRatesJson(rates));
    if (const SweepRates sweeps = sweepRates(rates.seeds); !sweeps.empty())
        writeSweepRateTables(sweeps, outDir);
}

namespace {

/// The rows of a report as they are written: an indented entry ("  per label") belongs to the
/// one above it.
class ReportRows {
public:
    void line(const std::string& what, const Rate& rate) {
        ReportRow row = split(what);
        row.rate = rate;
        rows_.push_back(row);
    }
    void push_back(const std::string& text) { rows_.push_back(split(text)); }
    void perLabel(const RatesByLabel& rates) {
        if (rates.size() > 1)
            for (const auto& [label, rate] : rates) line("  " + label, rate);
    }
    std::vector<ReportRow> rows() && { return std::move(rows_); }

private:
    static ReportRow split(const std::string& text) {
        ReportRow row;
        std::size_t at = 0;
        while (at < text.size() && text[at] == ' ') ++at;
        row.indent = static_cast<int>(at / 2);
        row.what = text.substr(at);
        return row;
    }
    std::vector<ReportRow> rows_;
};

/// Runs failed, trials lost and completed, and where and round which corners.
void reportTrials(ReportRows& lines, const SeedRates& r) {
    char buf[200];
    if (const Rate failed = r.runsFailed(); failed.count > 0) {
        // A device or rig error is no outcome of the method: such runs count in no trial rate.
        lines.line("runs failed (device or rig error)", failed);
        for (const SeedOutcome& o : r.seeds)
            if (o.failed())
                lines.push_back("  seed " + std::to_string(o.seed) + ", " +
                                std::to_string(o.trialsNotRun) +
                                " trials not run: " + o.runFailure);
    }
    lines.line("passive trials lost", r.passiveLost());
    lines.perLabel(r.passiveLostByLabel());
    lines.line("passive trials lost at a corner", r.passiveLostAtCorner());
    lines.line("active trials completed", r.activeCompleted());
    lines.perLabel(r.activeCompletedByLabel());
    // Where the active trials that did not complete got stuck, and how often each kind of corner
    // was got round in each mode.
    if (const CornerTally c = r.corners(FollowingMode::Active); c.notCompleted() > 0) {
        std::snprintf(buf, sizeof buf,
                      "  not completed, furthest near a convex corner %d, a concave corner %d, "
                      "no corner %d",
                      c.endedConvex, c.endedConcave, c.endedAway);
        lines.push_back(buf);
    }
    for (const FollowingMode mode : {FollowingMode::Active, FollowingMode::Passive}) {
        const CornerTally c = r.corners(mode);
        const std::string m = modeName(mode);
        if (c.convexRounded().total > 0)
            lines.line("convex corners got round, " + m, c.convexRounded());
        if (c.concaveRounded().total > 0)
            lines.line("concave corners got round, " + m, c.concaveRounded());
    }
    // Where the validation put the valid range decides where the active tip runs, so completion
    // is given per valid range when the runs picked more than one.
    if (const auto byRange = r.activeCompletedByValidRange(); byRange.size() > 1) {
        lines.push_back("active trials completed by the valid range each run picked:");
        for (const ValidRangeRate& v : byRange)
            lines.line("  " + v.range.span() + " mm, " + std::to_string(v.runs) +
                           (v.runs == 1 ? " run" : " runs"),
                       v.activeCompleted);
    }
}

/// Paths recognised by each rule, what they were misnamed as, and the pose recovered.
void reportRecognition(ReportRows& lines, const SeedRates& r) {
    const RecognitionConfusion confusion = r.confusion();
    lines.line("recognised, paper's rule", r.recognisedRaw());
    lines.perLabel(r.recognisedRawByTrial());
    if (const std::string m = confusion.misnamed(false); !m.empty())
        lines.push_back("  misnamed: " + m);
    lines.line("recognised, smoothed histograms", r.recognisedSmoothed());
    if (const std::string m = confusion.misnamed(true); !m.empty())
        lines.push_back("  misnamed: " + m);
    if (r.recognisedAnyPose().total == 0) return;
    lines.line("recognised at any pose", r.recognisedAnyPose());
    if (const std::string m = confusion.misnamedAnyPose(); !m.empty())
        lines.push_back("  misnamed: " + m);
    if (r.medianTurnError_deg() >= 0) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "recovered at any pose: turn off by %.2f deg, place by %.2f mm (medians)",
                      r.medianTurnError_deg(), r.medianPlaceError_mm());
        lines.push_back(buf);
    }
}

/// Runs with the paper's result whole, what a completed trial costs, and how closely completed
/// trials traced the contour (passive only if any got round).
void reportWholeRunsAndCosts(ReportRows& lines, const SeedRates& r) {
    char buf[200];
    lines.line("runs with the paper's result whole", r.paperResult());
    lines.line("runs whole, smoothed histograms", r.paperResultSmoothed());
    if (const ShortOfPaper s = r.shortOfPaper(); s.runs > 0) {
        std::snprintf(buf, sizeof buf,
                      "runs short: %d (passive not lost at a corner %d, active lost %d, path "
                      "misnamed %d)",
                      s.runs, s.passiveNotLost, s.activeLost, s.misnamedRaw);
        lines.push_back(buf);
    }
    if (r.activeCompleted().count > 0) {
        std::snprintf(buf, sizeof buf,
                      "completed active trial: %.0f taps, %.0f s robot time; whole run %.0f s",
                      r.tapsPerCompletedTrial(), r.robotTimePerCompletedTrial_s(),
                      r.robotTimePerRun_s());
        lines.push_back(buf);
    }
    for (const FollowingMode mode : {FollowingMode::Active, FollowingMode::Passive}) {
        const Tracing t = r.tracing(mode);
        if (t.trials == 0) continue;
        std::snprintf(buf, sizeof buf,
                      "completed %s trials: %.1f %% of the contour covered, mean distance %.2f "
                      "mm (%d)",
                      modeName(mode), 100.0 * t.coverage(), t.meanDistance_mm(), t.trials);
        lines.push_back(buf);
    }
}

}  // namespace

std::vector<ReportRow> rateReport(const SeedRates& r) {
    ReportRows lines;
    reportTrials(lines, r);
    reportRecognition(lines, r);
    reportWholeRunsAndCosts(lines, r);
    return std::move(lines).rows();
}

std::vector<std::string> describeRates(const SeedRates& r) {
    const std::vector<ReportRow> rows = rateReport(r);
    // Rate lines have their counts as wide as the widest (four digits at least).
    int digits = 4;
    for (const ReportRow& row : rows)
        if (row.rate)
            digits = std::max(digits, static_cast<int>(std::to_string(row.rate->total).size()));
    std::vector<std::string> lines;
    char buf[300];
    for (const ReportRow& row : rows) {
        const std::string what = std::string(2 * std::size_t(row.indent), ' ') + row.what;
        if (!row.rate)
            lines.push_back(what);
        else if (row.rate->total == 0)
            std::snprintf(buf, sizeof buf, "%-34s  none in this experiment", what.c_str());
        else
            std::snprintf(
                buf, sizeof buf, "%-34s %*d / %-*d %5.1f %%  (95 %% interval %5.1f-%5.1f %%)",
                what.c_str(), digits, row.rate->count, digits, row.rate->total,
                100.0 * row.rate->fraction(), 100.0 * row.rate->low(), 100.0 * row.rate->high());
        if (row.rate) lines.push_back(buf);
    }
    return lines;
}

void startRatesTable(std::optional<OutputFile>& file, const std::string& outDir) {
    startAppendedTable(file, outDir, "rates.csv", "rates.json",
                       "seed,passive_trials,passive_lost,passive_lost_at_a_corner,active_trials,"
                       "active_completed,"
                       "recognition_trials,recognised_raw,recognised_smoothed,completed_taps,"
                       "completed_robot_time_s,"
                       "run_robot_time_s,validation_angle_error_deg,validation_position_error_mm,"
                       "valid_range_positions,"
                       "paper_result,paper_result_smoothed,active_failures,misnamed_paths,"
                       "passive_not_lost_at_a_corner,run_failure,trials_not_run\n");
}

void appendRatesRow(OutputFile& file, const SeedOutcome& o) {
    // Where the experiment does not have the paper's parts, its result is left empty.
    const char* paper = !o.paperResultApplies() ? "" : o.paperResult() ? "1" : "0";
    const char* smoothed = !o.paperResultApplies() ? "" : o.paperResultSmoothed() ? "1" : "0";
    file.print("%llu,%d,%d,%d,%d,%d,%d,%d,%d,%d,%.3f,%.3f,%.4f,%.4f,%s,%s,%s,%s,%s,%s,%s,%d\n",
               static_cast<unsigned long long>(o.seed), o.passiveTrials, o.passiveLost,
               o.passiveLostAtCorner(), o.activeTrials, o.activeCompleted, o.recognitionTrials(),
               o.recognisedRaw(), o.recognisedSmoothed(), o.completedTaps, o.completedRobotTime_s,
               o.runRobotTime_s, o.angleError_deg, o.positionError_mm, o.validRange.span().c_str(),
               paper, smoothed, csvField(o.failures).c_str(), csvField(o.misnamed()).c_str(),
               csvField(o.passiveShortfalls).c_str(),
               o.failed() ? csvField({o.runFailure}).c_str() : "", o.trialsNotRun);
    file.flush();
}

SeedRates runSeeds(const SimulatedRigs& rigs, const ExperimentSpec& spec, std::uint64_t first,
                   std::uint64_t last, const std::string& outDir,
                   const std::function<bool(const SeedOutcome&)>& seedDone, int jobs,
                   const std::vector<SeedOutcome>& before) {
    SeedRates rates;
    std::optional<OutputFile> file;
    if (!outDir.empty()) startRatesTable(file, outDir);
    for (const SeedOutcome& o : before) {
        rates.seeds.push_back(o);
        if (file) appendRatesRow(*file, o);
    }
    const auto run = [&spec, &rigs](std::uint64_t seed) {
        RunOptions options;
        options.simulated = &rigs;
        options.seed = seed;
        options.reportsBeliefCalibration = false;  // an outcome does not carry it
        return seedOutcome(runExperimentOrFailure(spec, options));
    };
    forEachSeed(first, last, jobs, run, [&](std::uint64_t, SeedOutcome&& o) {
        rates.seeds.push_back(o);
        if (file) appendRatesRow(*file, o);
        return !seedDone || seedDone(o);
    });
    if (file) {
        file->close();
        writeSeedRatesFiles(rates, outDir);
    }
    return rates;
}

}  // namespace activetouch
