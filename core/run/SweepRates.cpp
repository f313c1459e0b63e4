#include "core/stats/Distributions.h"
#include "core/stats/Intervals.h"
#include "core/stats/Resampling.h"
#include "core/run/SweepRates.h"

#include <algorithm>
#include <cstdarg>
#include <string_view>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>

#include "core/run/OutputFiles.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr int kResamples = 2000;

std::pair<double, double> asPair(const stats::Interval& i) {
    return {i.low, i.high};
}

struct SettingSums {
    double time = 0, completed = 0;
};

double ratio(const SettingSums& s) {
    return s.completed > 0 ? s.time / s.completed : kInf;
}

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

std::string thresholdName(double threshold) {
    if (threshold <= 0) return "single tap";
    char buf[48];
    std::snprintf(buf, sizeof buf, "threshold %g", threshold);
    return buf;
}

std::string settingName(FollowingMode mode, double follow, double reposition, double threshold) {
    char buf[96];
    if (mode == FollowingMode::Active)
        std::snprintf(buf, sizeof buf, "active %g/%g mm, %s", follow, reposition,
                      thresholdName(threshold).c_str());
    else
        std::snprintf(buf, sizeof buf, "passive %g mm, %s", follow,
                      thresholdName(threshold).c_str());
    return buf;
}

template <typename Row>
std::string settingName(const Row& r) {  // a row of (b), per run or over seeds
    return settingName(r.mode, r.followStep_mm, r.repositionStep_mm, r.beliefThreshold);
}

/// `first` followed by `rest`: the single tap then the thresholds, the base then the faults.
template <typename Row>
std::vector<Row> firstThen(const Row& first, const std::vector<Row>& rest) {
    std::vector<Row> all{first};
    all.insert(all.end(), rest.begin(), rest.end());
    return all;
}

/// A number a seed keeps: non-finite values as null, read back as NaN.
Json kept(double v) {
    return std::isfinite(v) ? Json(v) : Json();
}
double keptOf(const Json& j) {
    return j.is_null() ? std::nan("") : j.get<double>();
}

}  // namespace

SweepEstimate overSeeds(const std::vector<double>& perSeed, double least, double most) {
    const stats::MeanInterval m = stats::studentMean(perSeed, least, most);
    return {m.mean, m.low, m.high};
}

PaperVerdict paperVerdict(const FollowingOverSeeds& f) {
    const SweepEstimate &c = f.completionDifference_points, &r = f.timeRatio;
    const bool informative = f.pairedSeeds >= kMinVerdictSeeds && std::isfinite(r.low) &&
                             std::isfinite(r.high) && r.high > r.low && std::isfinite(c.low) &&
                             std::isfinite(c.high) && c.high > c.low;
    if (!informative) return PaperVerdict::NotEnoughSeeds;
    return r.high < 1.0 && c.low > -kCompletionMargin_points ? PaperVerdict::Beats
                                                            : PaperVerdict::DoesNotBeat;
}

SweepRates sweepRates(const std::vector<SeedOutcome>& all) {
    SweepRates out;
    std::vector<const SweepResults*> runs;
    for (const SeedOutcome& s : all)
        if (!s.failed() && !s.sweeps.empty()) runs.push_back(&s.sweeps);
    out.seeds = static_cast<int>(runs.size());
    if (runs.empty()) return out;
    const SweepResults& first = *runs.front();

    // (a): each figure the mean of the seeds' means; an angle error only where the seed had edge
    // decisions, a plane (air) share only where it had plane (air) decisions.
    auto perception = [&](auto rowOf, double threshold) {
        PerceptionOverSeeds p;
        p.threshold = threshold;
        std::vector<double> taps, time, angle, position, correct, angleFall, positionFall, plane,
            air;
        for (const SweepResults* r : runs) {
            const PerceptionSweepRow* row = rowOf(*r);
            if (!row || row->decisions == 0) continue;
            ++p.seeds;
            taps.push_back(row->meanTaps);
            time.push_back(row->meanRobotTime_s);
            angle.push_back(row->angleError_deg);
            position.push_back(row->positionError_mm);
            correct.push_back(row->correctFraction);
            angleFall.push_back(row->angleFall_deg.mean);
            positionFall.push_back(row->positionFall_mm.mean);
            if (row->planeDecisions > 0) plane.push_back(row->planeRecognised);
            if (row->airDecisions > 0) air.push_back(row->airRecognised);
        }
        p.taps = overSeeds(taps, 1.0);
        p.robotTime_s = overSeeds(time, 0.0);
        p.angle_deg = overSeeds(angle, 0.0);
        p.position_mm = overSeeds(position, 0.0);
        p.correct = overSeeds(correct, 0.0, 1.0);
        p.angleFall_deg = overSeeds(angleFall);
        p.positionFall_mm = overSeeds(positionFall);
        p.planeRecognised = overSeeds(plane, 0.0, 1.0);
        p.airRecognised = overSeeds(air, 0.0, 1.0);
        return p;
    };
    for (std::size_t i = 0; i < first.perception.size(); ++i)
        out.perception.push_back(perception(
            [i](const SweepResults& r) {
                return i < r.perception.size() ? &r.perception[i] : nullptr;
            },
            first.perception[i].threshold));
    if (!first.perception.empty())
        out.perceptionSingleTap = perception(
            [](const SweepResults& r) {
                return r.perception.empty() ? nullptr : &r.perceptionSingleTap;
            },
            0.0);

    std::vector<double> raw, calibrated, ideal;
    for (const SweepResults* r : runs) {
        const PerceptionSweepCalibration& c = r->perceptionCalibration;
        if (!c.measured) continue;
        ++out.calibrationSeeds;
        out.calibrationWithin005 += c.eceCalibrated <= 0.05;
        raw.push_back(c.eceRaw);
        calibrated.push_back(c.eceCalibrated);
        ideal.push_back(c.eceIfCalibrated);
    }
    out.eceRaw = overSeeds(raw, 0.0, 1.0);
    out.eceCalibrated = overSeeds(calibrated, 0.0, 1.0);
    out.eceIfCalibrated = overSeeds(ideal, 0.0, 1.0);

    // (b): per setting, and paired with the paper's setting of the same mode seed by seed.
    const std::size_t settings = first.following.size();
    std::vector<std::vector<SettingSums>> sums(settings);  // [setting][run]
    for (std::size_t i = 0; i < settings; ++i) {
        const FollowingSweepRow& head = first.following[i];
        FollowingOverSeeds f;
        f.mode = head.mode;
        f.followStep_mm = head.followStep_mm;
        f.repositionStep_mm = head.repositionStep_mm;
        f.beliefThreshold = head.beliefThreshold;
        f.paperSetting = head.paperSetting;
        std::vector<double> distance, time, taps;
        SettingSums total;
        for (const SweepResults* r : runs) {
            SettingSums s;
            if (i < r->following.size() && r->following[i].trials > 0) {
                const FollowingSweepRow& row = r->following[i];
                ++f.seeds;
                f.completed.count += row.completed;
                f.completed.total += row.trials;
                distance.push_back(row.meanContourDistance_mm);
                time.push_back(row.meanRobotTime_s);
                taps.push_back(row.meanTaps);
                s = {row.meanRobotTime_s * row.trials, double(row.completed)};
            }
            sums[i].push_back(s);
            total.time += s.time;
            total.completed += s.completed;
        }
        f.contourDistance_mm = overSeeds(distance, 0.0);
        f.robotTimePerTrial_s = overSeeds(time, 0.0);
        f.tapsPerTrial = overSeeds(taps, 0.0);
        f.robotTimePerCompletion_s.mean = ratio(total);
        out.following.push_back(f);
    }
    const std::size_t n = runs.size();
    // Resampled seeds, the same draws for every setting so that the pairs stay paired.
    std::vector<std::vector<std::size_t>> draws(kResamples, std::vector<std::size_t>(n));
    stats::ResamplingGenerator lcg{0x5eed5eedULL};
    for (auto& d : draws)
        for (auto& k : d) k = lcg.below(n);
    auto resampledTotal = [&](std::size_t setting, const std::vector<std::size_t>& d) {
        SettingSums t;
        for (std::size_t k : d) {
            t.time += sums[setting][k].time;
            t.completed += sums[setting][k].completed;
        }
        return t;
    };
    for (std::size_t i = 0; i < settings; ++i) {
        std::vector<double> values;
        for (const auto& d : draws) values.push_back(ratio(resampledTotal(i, d)));
        std::tie(out.following[i].robotTimePerCompletion_s.low,
                 out.following[i].robotTimePerCompletion_s.high) = asPair(stats::percentileInterval(values));
    }
    for (std::size_t i = 0; i < settings; ++i) {
        FollowingOverSeeds& f = out.following[i];
        std::size_t paper = settings;
        for (std::size_t j = 0; j < settings; ++j)
            if (out.following[j].paperSetting && out.following[j].mode == f.mode) paper = j;
        if (paper == settings || paper == i) continue;
        f.paired = true;
        std::vector<double> completion, distance;
        for (std::size_t k = 0; k < n; ++k) {
            const auto& rows = runs[k]->following;
            if (std::max(i, paper) >= rows.size() || rows[i].trials == 0 || rows[paper].trials == 0)
                continue;
            completion.push_back(100.0 * (double(rows[i].completed) / rows[i].trials -
                                          double(rows[paper].completed) / rows[paper].trials));
            distance.push_back(rows[i].meanContourDistance_mm - rows[paper].meanContourDistance_mm);
        }
        f.completionDifference_points = overSeeds(completion);
        if (completion.size() > 1 &&
            f.completionDifference_points.high == f.completionDifference_points.low) {
            // Every seed gave the same difference (each setting completed all its trials, say):
            // the seeds show no spread, which is no evidence of none. The interval is then the
            // score interval of a paired difference with no discordant pairs beyond those the
            // difference needs: +/- z^2 / (N + z^2) over the N paired trials (Tango's for a
            // difference of 0), so that it narrows only as trials accumulate.
            int pairedTrials = 0;
            for (std::size_t k = 0; k < n; ++k) {
                const auto& rows = runs[k]->following;
                if (std::max(i, paper) < rows.size() && rows[i].trials > 0 &&
                    rows[paper].trials > 0)
                    pairedTrials += std::min(rows[i].trials, rows[paper].trials);
            }
            const double z = stats::normalTwoSided(), z2 = z * z;
            SweepEstimate& c = f.completionDifference_points;
            const double half = 100.0 * z2 / (pairedTrials + z2);
            c.low = std::max(-100.0, c.mean - half);
            c.high = std::min(100.0, c.mean + half);
        }
        f.distanceDifference_mm = overSeeds(distance);
        std::vector<double> ratios;
        for (const auto& d : draws)
            ratios.push_back(ratio(resampledTotal(i, d)) / ratio(resampledTotal(paper, d)));
        SettingSums mine, theirs;
        for (std::size_t k = 0; k < n; ++k) {
            mine.time += sums[i][k].time, mine.completed += sums[i][k].completed;
            theirs.time += sums[paper][k].time, theirs.completed += sums[paper][k].completed;
        }
        f.timeRatio.mean = ratio(mine) / ratio(theirs);
        std::tie(f.timeRatio.low, f.timeRatio.high) = asPair(stats::percentileInterval(ratios));
        f.pairedSeeds = static_cast<int>(completion.size());
        f.verdict = paperVerdict(f);
        f.beatsPaper = f.verdict == PaperVerdict::Beats;
    }
    // The front: no other setting at most as slow per completion, at least as complete and at
    // most as far from the contour, and better in one of them.
    for (FollowingOverSeeds& f : out.following) {
        const double t = f.robotTimePerCompletion_s.mean, c = f.completed.fraction(),
                     d = f.contourDistance_mm.mean;
        f.onParetoFront = f.completed.count > 0;
        for (const FollowingOverSeeds& g : out.following) {
            const double tg = g.robotTimePerCompletion_s.mean, cg = g.completed.fraction(),
                         dg = g.contourDistance_mm.mean;
            if (tg <= t && cg >= c && dg <= d && (tg < t || cg > c || dg < d))
                f.onParetoFront = false;
        }
    }

    // (d): each seed's choice against that seed's best, and against the best over seeds.
    {
        BanditOverSeeds& b = out.bandit;
        int pooledBest = -1;
        double pooledBestReward = -kInf;
        std::vector<double> pooledReward(out.following.size(), -kInf);
        for (const SweepResults* r : runs) {
            if (!r->bandit.ran) continue;
            b.completionWorth_s = r->bandit.completionWorth_s;
        }
        for (std::size_t i = 0; i < out.following.size() && b.completionWorth_s > 0; ++i) {
            const FollowingOverSeeds& f = out.following[i];
            if (f.mode != FollowingMode::Active || f.completed.total == 0) continue;
            pooledReward[i] =
                f.completed.fraction() - f.robotTimePerTrial_s.mean / b.completionWorth_s;
            if (pooledReward[i] > pooledBestReward)
                pooledBestReward = pooledReward[i], pooledBest = int(i);
        }
        b.pooledBest = pooledBest;
        std::vector<double> regret, pooled;
        std::map<int, int> chosen;
        for (const SweepResults* r : runs) {
            const BanditResult& x = r->bandit;
            if (!x.ran || x.chosen < 0 || x.sweepBest < 0) continue;
            ++b.seeds;
            b.choseBest += x.chosen == x.sweepBest;
            regret.push_back(x.bestSweepReward - x.chosenSweepReward);
            const int row = x.arms[std::size_t(x.chosen)].sweepRow;
            ++chosen[row];
            if (row >= 0 && std::size_t(row) < pooledReward.size())
                pooled.push_back(pooledBestReward - pooledReward[std::size_t(row)]);
            b.robotTime_s += x.robotTime_s;
            b.sweepRobotTime_s += x.sweepRobotTime_s;
        }
        b.regret = overSeeds(regret, 0.0);
        b.pooledRegret = overSeeds(pooled, 0.0);
        for (const auto& [row, count] : chosen) b.choices.push_back({row, count});
        std::stable_sort(b.choices.begin(), b.choices.end(),
                         [](const auto& a, const auto& c) { return a.second > c.second; });
    }

    // (e): each fault's rates, and its fall below the same seed's fault-free run.
    auto robustness = [&](auto rowOf, const std::string& fault) {
        RobustnessOverSeeds f;
        f.fault = fault;
        std::vector<double> completion, recognition, angle;
        for (const SweepResults* r : runs) {
            const RobustnessRow* row = rowOf(*r);
            if (!row) continue;
            ++f.seeds;
            if (!row->failure.empty()) {
                ++f.failedRuns;
                continue;
            }
            const RobustnessRow& base = r->robustnessBase;
            f.completed.count += row->activeCompleted;
            f.completed.total += row->activeTrials;
            f.recognisedRaw.count += row->recognisedRaw;
            f.recognisedRaw.total += row->recognitionTrials;
            f.recognisedAnyPose.count += row->recognisedAnyPose;
            f.recognisedAnyPose.total += row->recognitionTrials;
            angle.push_back(row->angleError_deg);
            // Falls over the trials run: completion, and paths completed and named rightly.
            if (row->activeTrials > 0 && base.activeTrials > 0 && base.failure.empty()) {
                completion.push_back(100.0 * (double(base.activeCompleted) / base.activeTrials -
                                              double(row->activeCompleted) / row->activeTrials));
                recognition.push_back(100.0 * (double(base.recognisedRaw) / base.activeTrials -
                                               double(row->recognisedRaw) / row->activeTrials));
            }
        }
        f.completionFall_points = overSeeds(completion);
        f.recognitionFall_points = overSeeds(recognition);
        f.angleError_deg = overSeeds(angle, 0.0);
        return f;
    };
    if (!first.robustness.empty()) {
        out.robustnessBase = robustness(
            [](const SweepResults& r) {
                return r.robustness.empty() ? nullptr : &r.robustnessBase;
            },
            "none");
        for (std::size_t i = 0; i < first.robustness.size(); ++i)
            out.robustness.push_back(robustness(
                [i](const SweepResults& r) {
                    return i < r.robustness.size() ? &r.robustness[i] : nullptr;
                },
                first.robustness[i].fault));
    }

    for (std::size_t i = 0; i < first.compute.size(); ++i) {
        ComputeOverSeeds c;
        c.bins = first.compute[i].bins;
        c.samples = first.compute[i].samples;
        c.paperSetting = first.compute[i].paperSetting;
        std::vector<double> angle, position, us;
        for (const SweepResults* r : runs) {
            if (i >= r->compute.size()) continue;
            angle.push_back(r->compute[i].angleError_deg);
            position.push_back(r->compute[i].positionError_mm);
            us.push_back(r->compute[i].microsecondsPerDecision);
        }
        c.angle_deg = overSeeds(angle, 0.0);
        c.position_mm = overSeeds(position, 0.0);
        c.microsecondsPerDecision = overSeeds(us, 0.0);
        out.compute.push_back(c);
    }
    return out;
}

Json sweepRatesJson(const SweepRates& r) {
    Json perception = Json::array(), following = Json::array(), compute = Json::array();
    for (const auto& p : r.perception) perception.push_back(perceptionJson(p));
    for (const auto& f : r.following) {
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
        following.push_back(row);
    }
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

void writeSweepRateTables(const SweepRates& r, const std::string& dir) {
    auto finite = [](double v) { return std::isfinite(v) ? v : std::nan(""); };
    if (!r.perception.empty()) {
        OutputFile f((fs::path(dir) / "sweeps_perception.csv").string());
        cells(f, 
            "belief_threshold,seeds,mean_taps,mean_taps_lo,mean_taps_hi,robot_time_s,"
            "robot_time_s_lo,robot_time_s_hi,edge_angle_error_deg,edge_angle_error_deg_lo,"
            "edge_angle_error_deg_hi,position_error_mm,position_error_mm_lo,position_error_mm_hi,"
            "correct_fraction,correct_fraction_lo,correct_fraction_hi,angle_fall_deg,"
            "angle_fall_deg_lo,angle_fall_deg_hi,position_fall_mm,position_fall_mm_lo,"
            "position_fall_mm_hi,plane_as_plane,air_as_air\n");
        const std::vector<PerceptionOverSeeds> rows =
            firstThen(r.perceptionSingleTap, r.perception);
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
    if (!r.following.empty()) {
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
            cells(f, 
                "%s,%g,%g,%g,%d,%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.2f,%.3f,%.3f,%.3f",
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
    if (!r.robustness.empty()) {
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
    if (!r.compute.empty()) {
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
}

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
    if (!r.perception.empty()) {
        lines.push_back("  (a) sequential perception");
        lines.push_back(
            "    threshold   taps per decision     edge angle error (deg)   position error (mm)   "
            "angle fall (deg)      position fall (mm)");
        const std::vector<PerceptionOverSeeds> rows =
            firstThen(r.perceptionSingleTap, r.perception);
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
    if (!r.following.empty()) {
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
                buf, sizeof buf, "    %-32s %-23s %-22s %-25s %-30s %-20s%s",
                settingName(f).c_str(), completed,
                estimateText(f.contourDistance_mm, "%.2f").c_str(),
                std::isfinite(f.robotTimePerCompletion_s.mean)
                    ? estimateText(f.robotTimePerCompletion_s, "%.1f").c_str()
                    : "none completed",
                f.paired ? estimateText(f.completionDifference_points, "%+.1f").c_str() : "",
                f.paired && std::isfinite(f.timeRatio.mean)
                    ? estimateText(f.timeRatio, "%.2f").c_str()
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
        lines.push_back("    (a dash: no value; no trial of that setting completed, or no seed "
                        "had such decisions)");
    }
    if (!r.robustness.empty()) {
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
            std::snprintf(buf, sizeof buf, "    %-19s %-25s %-22s %-27s %s%s",
                          base ? "none (base)" : f.fault.c_str(), completed,
                          base ? "" : estimateText(f.completionFall_points, "%+.1f").c_str(),
                          recognised,
                          base ? "" : estimateText(f.recognitionFall_points, "%+.1f").c_str(),
                          failed.c_str());
            lines.push_back(buf);
        }
    }
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
    if (!r.compute.empty()) {
        lines.push_back("  (c) compute");
        for (const auto& c : r.compute) {
            std::snprintf(buf, sizeof buf,
                          "    %3d bins x %2d samples: angle %s deg, position %s mm, %.2f us per "
                          "decision%s",
                          c.bins, c.samples, estimateText(c.angle_deg, "%.1f").c_str(),
                          estimateText(c.position_mm, "%.2f").c_str(),
                          c.microsecondsPerDecision.mean, c.paperSetting ? "  (paper)" : "");
            lines.push_back(buf);
        }
    }
    return lines;
}

namespace {

Json robustnessRowJson(const RobustnessRow& r) {
    return {{"fault", r.fault},
            {"failure", r.failure},
            {"active_trials", r.activeTrials},
            {"active_completed", r.activeCompleted},
            {"recognition_trials", r.recognitionTrials},
            {"recognised_raw", r.recognisedRaw},
            {"recognised_any_pose", r.recognisedAnyPose},
            {"validation_angle_error_deg", kept(r.angleError_deg)},
            {"validation_position_error_mm", kept(r.positionError_mm)}};
}

RobustnessRow robustnessRowOf(const Json& j) {
    RobustnessRow r;
    r.fault = j.at("fault").get<std::string>();
    r.failure = j.at("failure").get<std::string>();
    r.activeTrials = j.at("active_trials").get<int>();
    r.activeCompleted = j.at("active_completed").get<int>();
    r.recognitionTrials = j.at("recognition_trials").get<int>();
    r.recognisedRaw = j.at("recognised_raw").get<int>();
    r.recognisedAnyPose = j.at("recognised_any_pose").get<int>();
    r.angleError_deg = keptOf(j.at("validation_angle_error_deg"));
    r.positionError_mm = keptOf(j.at("validation_position_error_mm"));
    return r;
}

Json keptBandit(const BanditResult& b) {
    if (!b.ran) return Json();
    Json arms = Json::array();
    for (const BanditArm& a : b.arms)
        arms.push_back({a.sweepRow, a.followStep_mm, a.repositionStep_mm, a.beliefThreshold,
                        a.pulls, a.completed, kept(a.rewardSum), kept(a.robotTime_s)});
    return {{"worth_s", b.completionWorth_s},
            {"rounds", b.rounds},
            {"chosen", b.chosen},
            {"best", b.sweepBest},
            {"chosen_reward", kept(b.chosenSweepReward)},
            {"best_reward", kept(b.bestSweepReward)},
            {"robot_time_s", kept(b.robotTime_s)},
            {"sweep_robot_time_s", kept(b.sweepRobotTime_s)},
            {"arms", arms}};
}

BanditResult keptBanditOf(const Json& j) {
    BanditResult b;
    if (j.is_null()) return b;
    b.ran = true;
    b.completionWorth_s = keptOf(j.at("worth_s"));
    b.rounds = j.at("rounds").get<int>();
    b.chosen = j.at("chosen").get<int>();
    b.sweepBest = j.at("best").get<int>();
    b.chosenSweepReward = keptOf(j.at("chosen_reward"));
    b.bestSweepReward = keptOf(j.at("best_reward"));
    b.robotTime_s = keptOf(j.at("robot_time_s"));
    b.sweepRobotTime_s = keptOf(j.at("sweep_robot_time_s"));
    for (const Json& a : j.at("arms"))
        b.arms.push_back({a.at(0).get<int>(), keptOf(a.at(1)), keptOf(a.at(2)), keptOf(a.at(3)),
                          a.at(4).get<int>(), a.at(5).get<int>(), keptOf(a.at(6)),
                          keptOf(a.at(7))});
    const int A = static_cast<int>(b.arms.size());
    if (b.chosen < 0 || b.chosen >= A || b.sweepBest < 0 || b.sweepBest >= A)
        throw std::runtime_error("the bandit's chosen or best setting is not one of its arms");
    return b;
}

}  // namespace

Json robustnessJson(const SweepResults& s) {
    if (s.robustness.empty()) return Json();
    Json rows = Json::array();
    rows.push_back(robustnessRowJson(s.robustnessBase));
    for (const auto& r : s.robustness) rows.push_back(robustnessRowJson(r));
    return rows;
}

std::vector<std::string> describeRobustness(const SweepResults& s) {
    std::vector<std::string> lines;
    if (s.robustness.empty()) return lines;
    lines.push_back("robustness: the whole run again on this seed with one fault added:");
    const std::vector<RobustnessRow> all = firstThen(s.robustnessBase, s.robustness);
    for (const auto& r : all) {
        char buf[512];
        if (!r.failure.empty())
            std::snprintf(buf, sizeof buf, "  %-18s failed: %s", r.fault.c_str(),
                          r.failure.c_str());
        else
            std::snprintf(buf, sizeof buf,
                          "  %-18s active completed %d/%d, recognised by the paper's rule %d/%d, "
                          "validation %.1f deg, %.2f mm",
                          r.fault == "none" ? "none (base)" : r.fault.c_str(), r.activeCompleted,
                          r.activeTrials, r.recognisedRaw, r.recognitionTrials, r.angleError_deg,
                          r.positionError_mm);
        lines.push_back(buf);
    }
    return lines;
}

Json banditJson(const BanditResult& b, const std::vector<FollowingSweepRow>& following) {
    if (!b.ran) return Json();
    Json arms = Json::array();
    for (const BanditArm& a : b.arms)
        arms.push_back({{"setting", settingName(following[std::size_t(a.sweepRow)])},
                        {"sweep_row", a.sweepRow},
                        {"trials", a.pulls},
                        {"completed", a.completed},
                        {"robot_time_s", a.robotTime_s},
                        {"mean_reward", a.pulls > 0 ? Json(a.meanReward()) : Json()}});
    return {{"method", "UCB1 over the following sweep's active settings, each tried once first"},
            {"reward", "1 if the trial completed, less its robot time over completion_worth_s"},
            {"completion_worth_s", b.completionWorth_s},
            {"rounds", b.rounds},
            {"chosen", settingName(following[std::size_t(b.arms[std::size_t(b.chosen)].sweepRow)])},
            {"sweep_best",
             settingName(following[std::size_t(b.arms[std::size_t(b.sweepBest)].sweepRow)])},
            {"chosen_reward_in_sweep", b.chosenSweepReward},
            {"best_reward_in_sweep", b.bestSweepReward},
            {"robot_time_s", b.robotTime_s},
            {"sweep_robot_time_s", b.sweepRobotTime_s},
            {"arms", arms}};
}

std::string describeBandit(const BanditResult& b, const std::vector<FollowingSweepRow>& following) {
    if (!b.ran || b.chosen < 0) return "";
    const BanditArm& c = b.arms[std::size_t(b.chosen)];
    char buf[512];
    std::snprintf(
        buf, sizeof buf,
        "bandit: %d trials (%.0f s of robot time, %.0f %% of sweep (b)'s active "
        "settings) chose %s (%d trials); the sweep's best by the same reward (completion "
        "less robot time / %g s) is %s: %.3f against %.3f per trial",
        b.rounds, b.robotTime_s,
        b.sweepRobotTime_s > 0 ? 100.0 * b.robotTime_s / b.sweepRobotTime_s : 0.0,
        settingName(following[std::size_t(c.sweepRow)]).c_str(), c.pulls, b.completionWorth_s,
        b.chosen == b.sweepBest
            ? "the same"
            : settingName(following[std::size_t(b.arms[std::size_t(b.sweepBest)].sweepRow)])
                  .c_str(),
        b.chosenSweepReward, b.bestSweepReward);
    return buf;
}

Json seedSweepsJson(const SweepResults& s) {
    auto perception = [](const PerceptionSweepRow& p) {
        return Json::array({p.threshold, p.decisions, kept(p.meanTaps), kept(p.meanRobotTime_s),
                            kept(p.angleError_deg), kept(p.positionError_mm),
                            kept(p.correctFraction), kept(p.angleFall_deg.mean),
                            kept(p.positionFall_mm.mean), p.planeDecisions, kept(p.planeRecognised),
                            p.airDecisions, kept(p.airRecognised)});
    };
    Json rowsA = Json::array(), rowsB = Json::array(), rowsC = Json::array();
    for (const auto& p : s.perception) rowsA.push_back(perception(p));
    for (const auto& f : s.following)
        rowsB.push_back({modeName(f.mode), f.followStep_mm, f.repositionStep_mm, f.beliefThreshold,
                         f.paperSetting, f.trials, f.completed, kept(f.meanContourDistance_mm),
                         kept(f.meanTaps), kept(f.meanRobotTime_s)});
    for (const auto& c : s.compute)
        rowsC.push_back({c.bins, c.samples, kept(c.angleError_deg), kept(c.positionError_mm),
                         kept(c.microsecondsPerDecision), c.paperSetting});
    const PerceptionSweepCalibration& c = s.perceptionCalibration;
    return {{"perception", rowsA},
            {"single_tap", perception(s.perceptionSingleTap)},
            {"calibration",
             {c.measured, c.calibrated, c.taps, kept(c.eceRaw), kept(c.eceCalibrated),
              kept(c.eceIfCalibrated)}},
            {"following", rowsB},
            {"compute", rowsC},
            {"bandit", keptBandit(s.bandit)},
            {"robustness", robustnessJson(s)}};
}

SweepResults seedSweepsFromJson(const Json& j) {
    SweepResults s;
    auto perception = [](const Json& a) {
        PerceptionSweepRow p;
        p.threshold = keptOf(a.at(0));
        p.decisions = a.at(1).get<int>();
        p.meanTaps = keptOf(a.at(2));
        p.meanRobotTime_s = keptOf(a.at(3));
        p.angleError_deg = keptOf(a.at(4));
        p.positionError_mm = keptOf(a.at(5));
        p.correctFraction = keptOf(a.at(6));
        p.angleFall_deg.mean = keptOf(a.at(7));
        p.positionFall_mm.mean = keptOf(a.at(8));
        p.planeDecisions = a.at(9).get<int>();
        p.planeRecognised = keptOf(a.at(10));
        p.airDecisions = a.at(11).get<int>();
        p.airRecognised = keptOf(a.at(12));
        return p;
    };
    for (const Json& a : j.at("perception")) s.perception.push_back(perception(a));
    s.perceptionSingleTap = perception(j.at("single_tap"));
    const Json& c = j.at("calibration");
    s.perceptionCalibration = {c.at(0).get<bool>(), c.at(1).get<bool>(), c.at(2).get<int>(),
                               keptOf(c.at(3)),     keptOf(c.at(4)),     keptOf(c.at(5))};
    for (const Json& a : j.at("following")) {
        const auto mode = modeNamed(a.at(0).get<std::string>());
        if (!mode)
            throw std::runtime_error("unknown following mode '" + a.at(0).get<std::string>() + "'");
        FollowingSweepRow f{*mode, keptOf(a.at(1)), keptOf(a.at(2)), keptOf(a.at(3))};
        f.paperSetting = a.at(4).get<bool>();
        f.trials = a.at(5).get<int>();
        f.completed = a.at(6).get<int>();
        f.meanContourDistance_mm = keptOf(a.at(7));
        f.meanTaps = keptOf(a.at(8));
        f.meanRobotTime_s = keptOf(a.at(9));
        f.robotTimePerCompletion_s =
            f.completed > 0 ? f.meanRobotTime_s * f.trials / f.completed : kInf;
        s.following.push_back(f);
    }
    if (const auto bandit = j.find("bandit"); bandit != j.end()) {
        s.bandit = keptBanditOf(*bandit);
        for (const BanditArm& a : s.bandit.arms)
            if (a.sweepRow < 0 || std::size_t(a.sweepRow) >= s.following.size())
                throw std::runtime_error("a bandit setting is not a row of the following sweep");
    }
    if (const auto rows = j.find("robustness"); rows != j.end() && !rows->is_null()) {
        if (!rows->is_array() || rows->empty())
            throw std::runtime_error("'robustness' is not a list of runs");
        s.robustnessBase = robustnessRowOf(rows->at(0));
        for (std::size_t i = 1; i < rows->size(); ++i)
            s.robustness.push_back(robustnessRowOf(rows->at(i)));
    }
    for (const Json& a : j.at("compute")) {
        ComputeSweepRow row{a.at(0).get<int>(), a.at(1).get<int>(), keptOf(a.at(2)),
                            keptOf(a.at(3)), keptOf(a.at(4))};
        row.paperSetting = a.at(5).get<bool>();
        s.compute.push_back(row);
    }
    return s;
}

}  // namespace activetouch
