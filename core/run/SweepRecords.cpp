#include "core/run/SweepRecords.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace activetouch {

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

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A number a seed keeps: non-finite values as null, read back as NaN.
Json kept(double v) {
    return std::isfinite(v) ? Json(v) : Json();
}
double keptOf(const Json& j) {
    return j.is_null() ? std::nan("") : j.get<double>();
}

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
