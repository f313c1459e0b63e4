#include "core/analysis/OutcomeChecks.h"

#include <cmath>

#include "core/common/InputError.h"

namespace activetouch {
namespace {

/// `text` in single quotes (built by appending: GCC 12 warns wrongly on "'" + a temporary).
std::string quoted(const std::string& text) {
    std::string q(1, '\'');
    q += text;
    q += '\'';
    return q;
}

class Checker {
public:
    Checker(const std::string& path, const std::string& place) : path_(path), place_(place) {}

    void count(int value, const char* key) const {
        if (value < 0) fail(key, std::to_string(value) + " is below 0; a count cannot be");
    }
    void part(int value, int whole, const char* key, const char* wholeKey) const {
        count(value, key);
        count(whole, wholeKey);
        if (value > whole)
            fail(key, std::to_string(value) + " is more than its " + wholeKey + " (" +
                          std::to_string(whole) + ")");
    }
    void amount(double value, const char* key, double most) const {
        if (!std::isfinite(value) || value < 0.0 || value > most)
            fail(key, quoted(std::to_string(value)) + " is not a finite value within 0.." +
                          std::to_string(most));
    }
    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw InputError(path_, place_ + "/" + key,
                         what +
                             "; no run writes that, so the file was damaged or edited: run "
                             "that shard again");
    }

private:
    const std::string& path_;
    const std::string& place_;
};

void checkByLabel(const Checker& c, const RatesByLabel& rates, const char* key) {
    for (const auto& [label, rate] : rates) c.part(rate.count, rate.total, key, "total");
}

void checkTracing(const Checker& c, const Tracing& t, const char* key) {
    c.count(t.trials, key);
    c.amount(t.coverageSum, key, t.trials);
    c.amount(t.meanDistanceSum_mm, key, 1e6 * std::max(t.trials, 1));
}

void checkCorners(const Checker& c, const CornerTally& t, const char* key) {
    for (const int v :
         {t.endedConvex, t.endedConcave, t.endedAway, t.rounded.convex, t.rounded.concave})
        c.count(v, key);
}

}  // namespace

void checkSeedOutcome(const SeedOutcome& o, const std::string& path, const std::string& place) {
    const Checker c(path, place);
    c.part(o.passiveLost, o.passiveTrials, "passive_lost", "passive_trials");
    c.part(o.activeCompleted, o.activeTrials, "active_completed", "active_trials");
    c.count(o.completedTaps, "completed_taps");
    c.count(o.trialsNotRun, "trials_not_run");
    c.amount(o.completedRobotTime_s, "completed_robot_time_s", kMaxSeedRobotTime_s);
    c.amount(o.runRobotTime_s, "run_robot_time_s", kMaxSeedRobotTime_s);
    if (o.completedRobotTime_s > o.runRobotTime_s)
        c.fail("completed_robot_time_s",
               "the completed trials' robot time is more than the "
               "whole run's");
    c.amount(o.angleError_deg, "angle_error_deg", 180.0);
    c.amount(o.positionError_mm, "position_error_mm", 1e6);
    if (o.validRange.first > o.validRange.last || !std::isfinite(o.validRange.score))
        c.fail("valid_range", "the range runs backwards or its score is not finite");
    if (o.recognitionTrials() > o.activeCompleted)
        c.fail("namings", std::to_string(o.recognitionTrials()) +
                              " paths named, more than the completed active trials (" +
                              std::to_string(o.activeCompleted) + ")");
    checkByLabel(c, o.activeByLabel, "active_by_label");
    checkByLabel(c, o.passiveByLabel, "passive_by_label");
    checkTracing(c, o.activeTracing, "active_tracing");
    checkTracing(c, o.passiveTracing, "passive_tracing");
    checkCorners(c, o.activeCorners, "active_corners");
    checkCorners(c, o.passiveCorners, "passive_corners");
    for (const PathNaming& n : o.namings)
        if (!std::isfinite(n.turnError_deg) || !std::isfinite(n.placeError_mm))
            c.fail("namings", "a naming's turn or place error is not finite");
}

void checkSeedPairRecord(const SeedPairRecord& r, const std::string& path,
                         const std::string& place) {
    const Checker c(path, place);
    c.amount(r.robotTimeA_s, "robot_time_s", kMaxSeedRobotTime_s);
    c.amount(r.robotTimeB_s, "robot_time_s", kMaxSeedRobotTime_s);
    c.count(r.unpairedTrials, "unpaired_trials");
}

}  // namespace activetouch
