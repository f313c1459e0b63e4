#include "core/experiment/RunPlan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace activetouch {
namespace {

// 1234567 -> "1,234,567"; beyond 1e15, "1.2e+18".
std::string countText(double n) {
    if (!(n < 1e15)) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.2g", n);
        return buf;
    }
    std::string digits = std::to_string(static_cast<long long>(std::llround(n)));
    std::string out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

std::string durationText(double s) {
    char buf[48];
    if (s < 120)
        std::snprintf(buf, sizeof buf, "%.0f s", s);
    else if (s < 3 * 3600)
        std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
    else if (s < 3 * 86400)
        std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
    else if (s < 3 * 365.25 * 86400)
        std::snprintf(buf, sizeof buf, "%.0f days", s / 86400);
    else
        std::snprintf(buf, sizeof buf, "%.3g years", s / (365.25 * 86400));
    return buf;
}

}  // namespace

RunPlan RunPlan::times(double runs) const {
    RunPlan p = *this;
    p.trainingTaps *= runs;
    p.trialTaps *= runs;
    p.sweepTaps *= runs;
    p.robotTime_s *= runs;
    return p;  // runs one after another hold one run's taps at a time per job
}

RunPlan planOf(const ExperimentSpec& e) {
    RunPlan p;
    const double classes = e.classes.classCount();
    p.trainingTaps = double(e.training.dataSets) * classes * double(e.training.tapsPerClass);
    double perimeters = 0.0;  // of one trial of each spec, times its repeats
    for (const TrialSpec& t : e.trials)
        perimeters += double(t.repeats) * t.object.outline().perimeter();
    const double step = std::max(e.following.followStep_mm, 1e-3);
    const double decisionTaps =
        e.following.beliefThreshold > 0.0 ? double(e.following.maxTapsPerDecision) : 1.0;
    p.trialTaps = 1.2 * perimeters / step * decisionTaps;
    const SweepSpec& sw = e.sweeps;
    if (!sw.beliefThresholds.empty())
        p.sweepTaps += classes * std::max(2.0, double(sw.tapsPerClass)) * e.training.tapsPerClass;
    if (!sw.followSteps_mm.empty()) {
        double perSetting = 0.0;
        for (const TrialSpec& t : e.trials)
            for (double follow : sw.followSteps_mm)
                perSetting += 1.2 * t.object.outline().perimeter() / follow;
        p.sweepTaps += perSetting * double(sw.repositionSteps_mm.size()) *
                       double(sw.followingBeliefThresholds.size()) * double(sw.modes.size()) *
                       double(sw.followingRepeats);
        if (sw.bandit && !e.trials.empty()) {
            // Trials of an average object at an average follow step, as many as its rounds.
            const double active = double(sw.followSteps_mm.size() * sw.repositionSteps_mm.size() *
                                         sw.followingBeliefThresholds.size());
            const double rounds = sw.banditRounds > 0 ? sw.banditRounds : 4.0 * active;
            p.sweepTaps += rounds * perSetting / double(e.trials.size() * sw.followSteps_mm.size());
        }
    }
    // Each fault of a robustness sweep is the whole run again.
    p.sweepTaps += double(sw.faults.size()) * (p.trainingTaps + p.trialTaps);
    const TapSpec& tap = e.scene.tap;
    const double move_s = e.following.followStep_mm / e.scene.stage.speed_mm_s;
    p.robotTime_s = (p.trainingTaps + p.trialTaps) * (tap.window_s() + tap.settle_s + move_s);
    p.heldTapBytes = p.trainingTaps * double(tap.samples) *
                     double(std::max<std::size_t>(1, e.scene.fingertip.taxels.size())) *
                     sizeof(double);
    return p;
}

std::string planText(const RunPlan& p) {
    std::string s = countText(p.trainingTaps) + " training and test taps";
    if (p.trialTaps > 0) s += ", about " + countText(p.trialTaps) + " following taps";
    if (p.sweepTaps > 0) s += ", about " + countText(p.sweepTaps) + " sweep taps";
    s += "; about " + durationText(p.robotTime_s) + " of robot time";
    return s;
}

PlanProblem planProblem(const RunPlan& p, const std::string& what, bool onRig) {
    std::string over;
    if (!(p.taps() <= kMaxPlannedTaps))
        over = countText(p.taps()) + " taps (the bound is " + countText(kMaxPlannedTaps) + ")";
    else if (onRig && !(p.robotTime_s <= kMaxPlannedRobotTime_s))
        over = durationText(p.robotTime_s) + " of robot time (the bound is " +
               durationText(kMaxPlannedRobotTime_s) + ")";
    else if (!(p.heldTapBytes <= kMaxHeldTapBytes))
        over = countText(p.heldTapBytes / (1024.0 * 1024.0)) +
               " MiB of training taps held in memory (the bound is " +
               countText(kMaxHeldTapBytes / (1024.0 * 1024.0)) + " MiB)";
    if (over.empty()) return {};
    const double biggest = std::max({p.trainingTaps, p.trialTaps, p.sweepTaps});
    const bool memoryOnly =
        p.taps() <= kMaxPlannedTaps && (!onRig || p.robotTime_s <= kMaxPlannedRobotTime_s);
    PlanProblem problem;
    problem.place = memoryOnly                  ? "/scene/tap/samples"
                    : biggest == p.trainingTaps ? "/training"
                    : biggest == p.trialTaps    ? "/following/trials"
                                                : "/sweeps";
    problem.problem = what + " plans " + planText(p) + ": " + over +
                      "; check the counts there (data sets, taps per class, repeats, sweep "
                      "lists), or pass --allow-long-plan if this is meant";
    return problem;
}

}  // namespace activetouch
