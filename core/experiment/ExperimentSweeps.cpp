#include "core/experiment/ExperimentSweeps.h"

#include <algorithm>
#include <cmath>

#include "core/common/InputError.h"
#include "core/common/NumberText.h"

namespace activetouch {
namespace {

/// A non-empty list of numbers in (lo, hi) (or [lo, hi] when `closed`), refused otherwise.
std::vector<double> sweepRange(const JsonFields& f, const std::string& key, double lo, double hi,
                               bool closed, const std::string& what) {
    if (!f.raw(key).is_array() || f.raw(key).empty())
        f.fail(key, "'" + key + "' must be a non-empty list of " + what +
                        "; an empty sweep measures nothing");
    if (f.raw(key).size() > static_cast<std::size_t>(kMaxSweepValues))
        f.fail(key, "a sweep of " + std::to_string(f.raw(key).size()) + " values; at most " +
                        std::to_string(kMaxSweepValues) + " (split it into several experiments)");
    std::vector<double> v;
    for (std::size_t i = 0; i < f.raw(key).size(); ++i) {
        const Json& x = f.raw(key)[i];
        const bool number = x.is_number() && std::isfinite(x.get<double>());
        const double d = number ? x.get<double>() : 0.0;
        const bool inside = closed ? (d >= lo && d <= hi) : (d > lo && d < hi);
        if (!number || !inside)
            throw InputError(f.source(), f.placeOf(key) + "/" + std::to_string(i),
                             describeJson(x) + " is not " + what + " (" +
                                 (closed ? "from " : "strictly between ") + numberText(lo) +
                                 (closed ? " to " : " and ") + numberText(hi) + ")");
        v.push_back(d);
    }
    return v;
}

/// Sweep (a): belief thresholds for sequential perception.
void parsePerceptionSweep(const JsonFields& f, ExperimentSpec& e) {
    SweepSpec& s = e.sweeps;
    const JsonFields p = f.object("perception");
    p.rejectUnknownKeys({"belief_thresholds", "taps_per_class", "max_taps_per_decision"});
    if (!p.has("belief_thresholds"))
        p.fail("belief_thresholds",
               "missing 'belief_thresholds': the thresholds to sweep, each in (0, 1)");
    s.beliefThresholds = sweepRange(p, "belief_thresholds", 0.0, 1.0, false, "a belief threshold");
    s.tapsPerClass = p.integer("taps_per_class", 1, 100, s.tapsPerClass);
    s.maxTapsPerDecision = p.integer("max_taps_per_decision", 1, 100, s.maxTapsPerDecision);
}

/// Sweep (b): follow and repositioning steps, thresholds and modes.
void parseFollowingSweep(const JsonFields& f, ExperimentSpec& e) {
    SweepSpec& s = e.sweeps;
    const JsonFields p = f.object("following");
    p.rejectUnknownKeys(
        {"follow_steps_mm", "reposition_steps_mm", "belief_thresholds", "modes", "repeats"});
    for (const char* key : {"follow_steps_mm", "reposition_steps_mm"})
        if (!p.has(key))
            p.fail(key, std::string("missing '") + key + "': the step lengths to sweep, in mm");
    s.followSteps_mm = sweepRange(p, "follow_steps_mm", 0.0, 50.0, false, "a positive step length");
    s.repositionSteps_mm =
        sweepRange(p, "reposition_steps_mm", 0.0, 50.0, true, "a step length, 0 or more");
    s.followingBeliefThresholds = p.has("belief_thresholds")
                                      ? sweepRange(p, "belief_thresholds", 0.0, 1.0, true,
                                                   "0 (single tap) or a threshold below 1")
                                      : std::vector<double>{0.0};
    for (double t : s.followingBeliefThresholds)
        if (t >= 1.0) p.fail("belief_thresholds", "a belief threshold must be below 1");
    s.modes.clear();
    if (p.has("modes")) {
        if (!p.raw("modes").is_array() || p.raw("modes").empty())
            p.fail("modes", "'modes' must list active and/or passive");
        for (const auto& m : p.raw("modes")) {
            const auto mode = m.is_string() ? modeNamed(m.get<std::string>()) : std::nullopt;
            if (!mode)
                p.fail("modes", "mode " + describeJson(m) + " is neither active nor passive");
            s.modes.push_back(*mode);
        }
    } else {
        s.modes = {FollowingMode::Active, FollowingMode::Passive};
    }
    s.followingRepeats = p.integer("repeats", 1, 100, s.followingRepeats);
    if (e.trials.empty())
        p.fail("follow_steps_mm",
               "a following sweep needs trials (following.trials) to know which objects to "
               "follow");
}

/// Sweep (e): the faults each run is repeated with.
void parseRobustnessSweep(const JsonFields& f, ExperimentSpec& e) {
    const JsonFields p = f.object("robustness");
    p.rejectUnknownKeys({"dead_taxels", "gain_spreads", "crosstalk_couplings"});
    const int taxels = static_cast<int>(e.scene.fingertip.taxels.size());
    auto fault = [&](const std::string& name, const std::string& effect, const Json& parameters) {
        e.sweeps.faults.push_back({name, {effect, parameters, p.placeOf(name)}});
    };
    if (p.has("dead_taxels")) {
        const Json& d = p.raw("dead_taxels");
        std::vector<int> list;
        if (d.is_string() && d.get<std::string>() == "each") {
            for (int t = 0; t < taxels; ++t) list.push_back(t);
        } else if (d.is_array() && !d.empty()) {
            for (const Json& t : d) {
                if (!t.is_number_integer() || t.get<long>() < 0 || t.get<long>() >= taxels)
                    p.fail("dead_taxels", "taxel " + describeJson(t) + " is not a taxel index 0.." +
                                              std::to_string(taxels - 1));
                list.push_back(t.get<int>());
            }
        } else {
            p.fail("dead_taxels",
                   "'dead_taxels' is \"each\" (every taxel in turn) or a list of taxel indices");
        }
        for (int t : list)
            fault("dead taxel " + std::to_string(t), "dead_taxel",
                  {{"taxels", {t}}, {"reading_counts", 0}});
    }
    if (p.has("gain_spreads"))
        for (double g : sweepRange(p, "gain_spreads", 0.0, 1.0, false, "a gain spread in (0, 1)"))
            fault("gain spread " + numberText(g), "taxel_gain",
                  {{"spread", g}, {"fingertip_seed", 1}});
    if (p.has("crosstalk_couplings"))
        for (double c :
             sweepRange(p, "crosstalk_couplings", 0.0, 0.5, false, "a coupling in (0, 0.5)"))
            fault("crosstalk " + numberText(c), "crosstalk", {{"coupling", c}, {"radius_mm", 4.5}});
    if (e.sweeps.faults.empty())
        p.fail("dead_taxels",
               "a robustness sweep needs faults: dead_taxels, gain_spreads or "
               "crosstalk_couplings");
}

/// Sweep (d): the learner among sweep (b)'s active settings.
void parseBanditSweep(const JsonFields& f, ExperimentSpec& e) {
    SweepSpec& s = e.sweeps;
    const JsonFields p = f.object("bandit");
    p.rejectUnknownKeys({"rounds", "completion_worth_s"});
    if (s.followSteps_mm.empty() ||
        std::find(s.modes.begin(), s.modes.end(), FollowingMode::Active) == s.modes.end())
        p.fail("rounds",
               "the bandit learns among the following sweep's active settings: give "
               "sweeps.following with the active mode");
    s.bandit = true;
    s.banditRounds = p.integer("rounds", 0, 100000, 0);
    s.completionWorth_s = p.number("completion_worth_s", 1.0, 1e7, s.completionWorth_s);
}

/// Sweep (c): histogram bins and samples per tap.
void parseComputeSweep(const JsonFields& f, ExperimentSpec& e) {
    SweepSpec& s = e.sweeps;
    const JsonFields p = f.object("compute");
    p.rejectUnknownKeys({"bins", "samples_per_tap"});
    for (const char* key : {"bins", "samples_per_tap"})
        if (!p.has(key)) p.fail(key, std::string("missing '") + key + "'");
    for (double b : sweepRange(p, "bins", 1.0, 100000.0, true, "a whole number of bins")) {
        if (b != std::floor(b)) p.fail("bins", "bins must be whole numbers");
        s.bins.push_back(static_cast<int>(b));
    }
    for (double t :
         sweepRange(p, "samples_per_tap", 1.0, 100000.0, true, "a whole number of samples")) {
        if (t != std::floor(t) || t > e.scene.tap.samples)
            p.fail("samples_per_tap", "samples per tap must be whole numbers up to the tap's " +
                                          std::to_string(e.scene.tap.samples));
        s.samplesPerTap.push_back(static_cast<int>(t));
    }
}

}  // namespace

void parseSweeps(const JsonFields& f, ExperimentSpec& e) {
    f.rejectUnknownKeys({"perception", "following", "compute", "bandit", "robustness"});
    if (f.has("perception")) parsePerceptionSweep(f, e);
    if (f.has("following")) parseFollowingSweep(f, e);
    if (f.has("robustness")) parseRobustnessSweep(f, e);
    if (f.has("bandit")) parseBanditSweep(f, e);
    if (f.has("compute")) parseComputeSweep(f, e);
}

}  // namespace activetouch
