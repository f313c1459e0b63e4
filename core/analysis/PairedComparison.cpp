#include "core/analysis/PairedComparison.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/common/InputError.h"
#include "core/run/OutputFiles.h"
#include "core/run/RunArtefacts.h"
#include "core/stats/Intervals.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {

using TrialKey = std::tuple<FollowingMode, std::string, int>;

std::map<TrialKey, const TrialRun*> trialsByKey(const RunResult& run) {
    std::map<TrialKey, const TrialRun*> out;
    for (const TrialRun& t : run.trials) out[{t.result.mode, t.label, t.trial}] = &t;
    return out;
}

std::string percentText(double fraction) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * fraction);
    return buf;
}

std::string signedPercentText(double fraction) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+.1f %%", 100.0 * fraction);
    return buf;
}

Json pairedRateJson(const PairedRate& r) {
    return {{"pairs", r.pairs()},
            {"a", rateJson(r.a())},
            {"b", rateJson(r.b())},
            {"both", r.both},
            {"only_a", r.onlyA},
            {"only_b", r.onlyB},
            {"neither", r.neither},
            {"difference_b_minus_a", r.pairs() ? Json(r.difference()) : Json(nullptr)},
            {"difference_ci95",
             r.pairs() ? Json{r.differenceLow(), r.differenceHigh()} : Json(nullptr)},
            {"mcnemar_p", r.mcnemarP()}};
}

}  // namespace

std::string trialOutcome(const TrialRun& t) {
    const TrialResult& r = t.result;
    if (r.completed()) return "completed";
    return std::string(r.stoppedAtCorner() ? "lost at a corner (" : "lost away from corners (") +
           trialEndName(r.end) + ")";
}

std::string namedPath(const TrialRun& t) {
    return t.recognised && t.result.completed() ? t.recognition.predicted : std::string();
}

std::string endedText(const std::string& outcome, const std::string& named) {
    return named.empty() ? outcome : outcome + ", named " + named;
}

TrialPairRun runTrialPair(const SimulatedRigs& rigs, const ExperimentSpec& a,
                          const ExperimentSpec& b, std::uint64_t seed, FollowingMode mode,
                          const std::string& label, int trial) {
    for (const ExperimentSpec* spec : {&a, &b}) {
        int repeats = 0;
        for (const TrialSpec& t : spec->trials)
            if (t.mode == mode && t.label == label) repeats += t.repeats;
        if (trial < 1 || trial > repeats)
            throw InputError(spec->source.empty() ? spec->name : spec->source, "/following/trials",
                             "'" + spec->name + "' has no " + modeName(mode) + " trial " +
                                 std::to_string(trial) + " of '" + label +
                                 "'; choose a trial both experiments run");
    }
    RunOptions options;
    options.simulated = &rigs;
    options.seed = seed;
    TrialPairRun pair{a.name, b.name, seed, {}, {}};
    auto find = [&](const RunResult& run, TrialRun& out) {
        for (const TrialRun& t : run.trials)
            if (t.result.mode == mode && t.label == label && t.trial == trial) {
                out = t;
                return;
            }
        throw std::runtime_error("'" + run.spec.name + "' ended before its " + modeName(mode) +
                                 " trial " + std::to_string(trial) + " of '" + label + "'");
    };
    find(runExperiment(a, options), pair.a);
    find(runExperiment(b, options), pair.b);
    return pair;
}

std::string trialPairFileStem(const TrialPairRun& pair) {
    std::string label = pair.a.label;
    for (char& c : label)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return "trial_pair_seed" + std::to_string(pair.seed) + "_" + modeName(pair.a.result.mode) +
           "_" + label + "_" + std::to_string(pair.a.trial);
}

void writeTrialPairTable(const TrialPairRun& pair, const std::string& outDir) {
    ensureOutputDirectory(outDir);
    OutputFile f((fs::path(outDir) / (trialPairFileStem(pair) + ".csv")).string());
    f.print("side,experiment,%s\n", kTrialTapColumns);
    printTrialTaps(f, "a," + csvField({pair.nameA}) + ",", pair.a);
    printTrialTaps(f, "b," + csvField({pair.nameB}) + ",", pair.b);
    f.close();
}

void PairedRate::add(bool a, bool b) {
    if (a && b)
        ++both;
    else if (a)
        ++onlyA;
    else if (b)
        ++onlyB;
    else
        ++neither;
}

double PairedRate::difference() const {
    return pairs() > 0 ? double(onlyB - onlyA) / pairs() : 0.0;
}

double PairedRate::differenceLow() const {
    return stats::agrestiMinDifference(onlyA, onlyB, pairs()).interval.low;
}

double PairedRate::differenceHigh() const {
    return stats::agrestiMinDifference(onlyA, onlyB, pairs()).interval.high;
}

double PairedRate::mcnemarP() const {
    return stats::mcnemarExactP(onlyA, onlyB);
}

double PairedComparison::robotTimeDifferenceSd_s() const {
    if (seeds < 2) return 0.0;
    const double mean = (robotTimeSumB_s - robotTimeSumA_s) / seeds;
    return std::sqrt(std::max(0.0, (robotTimeDiffSquares - seeds * mean * mean) / (seeds - 1)));
}

SeedPairRecord seedPairRecord(const RunResult& a, const RunResult& b) {
    SeedPairRecord r;
    r.seed = a.spec.scene.seed;
    for (const auto& [side, run] : {std::pair{"a", &a}, std::pair{"b", &b}})
        if (!run->failure.empty())
            r.failedRuns.push_back("seed " + std::to_string(run->spec.scene.seed) + ", " + side +
                                   " (" + run->spec.name + "): " + run->failure);
    if (!r.failedRuns.empty()) return r;
    r.robotTimeA_s = a.robotTime_s;
    r.robotTimeB_s = b.robotTime_s;
    const auto inA = trialsByKey(a), inB = trialsByKey(b);
    for (const TrialRun& ta : a.trials) {  // in the order experiment A runs them
        const auto found = inB.find({ta.result.mode, ta.label, ta.trial});
        if (found == inB.end()) {
            ++r.unpairedTrials;
            continue;
        }
        const TrialRun& tb = *found->second;
        const TrialResult &ra = ta.result, &rb = tb.result;
        SeedPairRecord::Trial t;
        t.pair = {r.seed,           ra.mode,          ta.label,      ta.trial,
                  trialOutcome(ta), trialOutcome(tb), namedPath(ta), namedPath(tb)};
        t.completedA = ra.completed();
        t.completedB = rb.completed();
        t.atCornerA = ra.stoppedAtCorner();
        t.atCornerB = rb.stoppedAtCorner();
        t.recognitionApplies = ra.mode == FollowingMode::Active && t.completedA && t.completedB &&
                               ta.recognised && tb.recognised;
        t.namedRightA = t.recognitionApplies && ta.recognition.predicted == ta.label;
        t.namedRightB = t.recognitionApplies && tb.recognition.predicted == tb.label;
        r.trials.push_back(std::move(t));
    }
    for (const auto& entry : inB)
        if (!inA.count(entry.first)) ++r.unpairedTrials;
    const SeedOutcome oa = seedOutcome(a), ob = seedOutcome(b);
    r.paperResultApplies = oa.paperResultApplies() && ob.paperResultApplies();
    r.paperResultA = r.paperResultApplies && oa.paperResult();
    r.paperResultB = r.paperResultApplies && ob.paperResult();
    return r;
}

void addSeedRecord(PairedComparison& c, const SeedPairRecord& r, std::vector<PairedTrial>* trials) {
    c.records.push_back(r);
    if (!r.failedRuns.empty()) {
        c.failedRuns.insert(c.failedRuns.end(), r.failedRuns.begin(), r.failedRuns.end());
        return;
    }
    ++c.seeds;
    c.robotTimeSumA_s += r.robotTimeA_s;
    c.robotTimeSumB_s += r.robotTimeB_s;
    const double diff = r.robotTimeB_s - r.robotTimeA_s;
    c.robotTimeDiffSquares += diff * diff;
    c.unpairedTrials += r.unpairedTrials;
    for (const SeedPairRecord::Trial& t : r.trials) {
        if (t.pair.mode == FollowingMode::Active) {
            c.activeCompleted.add(t.completedA, t.completedB);
            if (t.recognitionApplies) c.recognisedRaw.add(t.namedRightA, t.namedRightB);
        } else {
            c.passiveLostAtCorner.add(t.atCornerA, t.atCornerB);
        }
        if (trials) trials->push_back(t.pair);
    }
    if (r.paperResultApplies) c.paperResult.add(r.paperResultA, r.paperResultB);
    c.soFar.push_back(static_cast<const PairedParts&>(c));
}

void addSeed(PairedComparison& c, const RunResult& a, const RunResult& b,
             std::vector<PairedTrial>* trials) {
    addSeedRecord(c, seedPairRecord(a, b), trials);
}

void checkComparable(const ExperimentSpec& a, const ExperimentSpec& b) {
    for (const TrialSpec& ta : a.trials)
        for (const TrialSpec& tb : b.trials)
            if (ta.label == tb.label && ta.mode == tb.mode) return;
    throw InputError(b.name, "/following/trials",
                     "no trial of '" + b.name + "' has a namesake in '" + a.name +
                         "' (the same label and mode); compare experiments that follow the same "
                         "trials");
}

void startComparisonTables(std::optional<OutputFile>& table, std::optional<OutputFile>& soFar,
                           const std::string& outDir) {
    startAppendedTable(table, outDir, "compare.csv", "compare.json",
                       "seed,mode,label,trial,outcome_a,outcome_b,named_a,named_b\n");
    startAppendedTable(soFar, outDir, "compare_so_far.csv", "compare.json",
                       "seeds_compared,seed,part,pairs,a,b,only_a,only_b,"
                       "difference_b_minus_a,ci95_low,ci95_high,mcnemar_p\n");
}

void appendComparedSeed(OutputFile& table, OutputFile& soFar, const PairedComparison& c,
                        const std::vector<PairedTrial>& pairs) {
    for (const PairedTrial& p : pairs)
        table.print("%llu,%s,%s,%d,%s,%s,%s,%s\n", static_cast<unsigned long long>(p.seed),
                    modeName(p.mode), csvField({p.label}).c_str(), p.trial, p.outcomeA.c_str(),
                    p.outcomeB.c_str(), p.namedA.c_str(), p.namedB.c_str());
    table.flush();
    const std::uint64_t seed = c.records.back().seed;
    for (const PairedPart& part : kPairedParts) {
        const PairedRate& r = c.*part.rate;
        if (r.pairs() == 0) continue;
        soFar.print("%d,%llu,%s,%d,%d,%d,%d,%d,%.6g,%.6g,%.6g,%.6g\n", c.seeds,
                    static_cast<unsigned long long>(seed), part.key, r.pairs(), r.a().count,
                    r.b().count, r.onlyA, r.onlyB, r.difference(), r.differenceLow(),
                    r.differenceHigh(), r.mcnemarP());
    }
    soFar.flush();
}

PairedComparison comparePaired(const SimulatedRigs& rigs, const ExperimentSpec& a,
                               const ExperimentSpec& b, std::uint64_t first, std::uint64_t last,
                               const std::string& outDir, const ComparedSeed& seedDone, int jobs) {
    PairedComparison c;
    c.nameA = a.name;
    c.nameB = b.name;
    checkComparable(a, b);
    std::optional<OutputFile> table, soFar;
    if (!outDir.empty()) startComparisonTables(table, soFar, outDir);
    const auto run = [&a, &b, &rigs](std::uint64_t seed) {
        RunOptions options;
        options.simulated = &rigs;
        options.seed = seed;
        options.reportsBeliefCalibration = false;  // the pairs are the trials' outcomes
        return std::make_pair(runExperimentOrFailure(a, options),
                              runExperimentOrFailure(b, options));
    };
    // Each seed in turn: its pairs into the comparison, then its rows into the tables.
    const auto record = [&](std::uint64_t seed, std::pair<RunResult, RunResult>&& runs) {
        SeedPairRecord r = seedPairRecord(runs.first, runs.second);
        r.seed = seed;
        std::vector<PairedTrial> pairs;
        addSeedRecord(c, r, &pairs);
        if (table) appendComparedSeed(*table, *soFar, c, pairs);
        return !seedDone || seedDone(seed, pairs, c);
    };
    forEachSeed(first, last, jobs, run, record);
    if (table) {
        table->close();
        soFar->close();
        writeJsonAtomically((fs::path(outDir) / "compare.json").string(), pairedComparisonJson(c));
    }
    return c;
}

Json pairedComparisonJson(const PairedComparison& c) {
    Json doc = {{"a", c.nameA},
                {"b", c.nameB},
                {"seeds", c.seeds},
                {"unpaired_trials", c.unpairedTrials},
                {"failed_runs", c.failedRuns}};
    for (const PairedPart& part : kPairedParts) doc[part.key] = pairedRateJson(c.*part.rate);
    doc["robot_time_per_run_s"] = {
        {"a", c.meanRobotTimeA_s()},
        {"b", c.meanRobotTimeB_s()},
        {"difference_b_minus_a", c.meanRobotTimeB_s() - c.meanRobotTimeA_s()},
        {"difference_sd", c.robotTimeDifferenceSd_s()}};
    return doc;
}

std::vector<std::string> describeComparison(const PairedComparison& c) {
    std::vector<std::string> lines;
    if (!c.failedRuns.empty()) {
        lines.push_back(std::to_string(c.failedRuns.size()) +
                        " failed runs (device or rig error), their seeds not compared:");
        for (const std::string& f : c.failedRuns) lines.push_back("  " + f);
    }
    char buf[320];
    std::snprintf(buf, sizeof buf, "A = %s, B = %s, %d seeds, trial by trial:", c.nameA.c_str(),
                  c.nameB.c_str(), c.seeds);
    lines.push_back(buf);
    std::snprintf(buf, sizeof buf, "  %-41s %-20s %-20s %6s %6s  %-28s %s", "", "A", "B", "only A",
                  "only B", "B - A (95 % interval)", "McNemar p");
    lines.push_back(buf);
    auto row = [&](const char* what, const PairedRate& r) {
        if (r.pairs() == 0) return;
        auto rate = [](const Rate& x) {
            return std::to_string(x.count) + "/" + std::to_string(x.total) + " " +
                   percentText(x.fraction());
        };
        const std::string diff = signedPercentText(r.difference()) + " (" +
                                 signedPercentText(r.differenceLow()) + " to " +
                                 signedPercentText(r.differenceHigh()) + ")";
        std::snprintf(buf, sizeof buf, "  %-41s %-20s %-20s %6d %6d  %-28s %.3g", what,
                      rate(r.a()).c_str(), rate(r.b()).c_str(), r.onlyA, r.onlyB, diff.c_str(),
                      r.mcnemarP());
        lines.push_back(buf);
    };
    for (const PairedPart& part : kPairedParts) row(part.name, c.*part.rate);
    auto minutes = [](double s) {
        return std::to_string(static_cast<int>(std::lround(s / 60.0))) + " min";
    };
    char spread[64] = "";
    if (c.seeds >= 2)  // one seed has no spread
        std::snprintf(spread, sizeof spread, " (sd %.1f min over the seeds)",
                      c.robotTimeDifferenceSd_s() / 60.0);
    std::snprintf(buf, sizeof buf, "  %-41s %-20s %-20s B - A %+.1f min per run%s",
                  "robot time per run", minutes(c.meanRobotTimeA_s()).c_str(),
                  minutes(c.meanRobotTimeB_s()).c_str(),
                  (c.meanRobotTimeB_s() - c.meanRobotTimeA_s()) / 60.0, spread);
    lines.push_back(buf);
    if (c.recognisedRaw.pairs() > 0)
        lines.push_back("  (recognition compared over the active trials both completed)");
    if (c.unpairedTrials > 0) {
        std::snprintf(buf, sizeof buf,
                      "  %d trials only one experiment has (label, mode or repeat) are not "
                      "compared",
                      c.unpairedTrials);
        lines.push_back(buf);
    }
    return lines;
}

}  // namespace activetouch
