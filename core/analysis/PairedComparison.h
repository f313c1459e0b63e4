#pragma once
// Two experiments compared on the same seeds and the same trials. A seed gives both experiments
// the same data sets and the same noise on each trial's world, so where they differ only in a
// setting (the classifier's kernel, a controller rule), comparing them trial by trial shows the
// setting's effect with far less noise than two rates with overlapping intervals: only the pairs
// whose outcomes differ carry information (McNemar's test).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/io/OutputFile.h"
#include "core/analysis/SeedRates.h"

namespace activetouch {

/// One yes/no outcome (a trial completed, say) over pairs of the same trial in experiments A and
/// B: how many pairs each said yes in, and in which they disagreed.
struct PairedRate {
    int both = 0, onlyA = 0, onlyB = 0, neither = 0;
    void add(bool a, bool b);
    int pairs() const { return both + onlyA + onlyB + neither; }
    Rate a() const { return {both + onlyA, pairs()}; }
    Rate b() const { return {both + onlyB, pairs()}; }
    /// B's rate minus A's, as a fraction of the pairs.
    double difference() const;
    /// The difference's 95 % interval (Agresti and Min's adjusted interval for paired
    /// proportions: half a pair added to each cell), within -1..1.
    double differenceLow() const;
    double differenceHigh() const;
    /// McNemar's exact two-sided p-value: how likely disagreements this lopsided (onlyA against
    /// onlyB) are if the two experiments did equally well. 1 where they never disagree.
    double mcnemarP() const;
};

/// A trial of one seed's run in both experiments, as each ended.
struct PairedTrial {
    std::uint64_t seed = 0;
    FollowingMode mode = FollowingMode::Active;
    std::string label;
    int trial = 1;
    /// "completed", "lost at a corner" or "lost away from corners", with the reason it ended.
    std::string outcomeA, outcomeB;
    std::string namedA, namedB;  ///< the shape the paper's rule named a completed path, or ""
    /// The two ended differently: one completed and the other not, or lost differently, or
    /// named the path differently.
    bool differs() const { return outcomeA != outcomeB || namedA != namedB; }
};

/// The parts of the paper's result, each compared over the pairs both experiments have.
struct PairedParts {
    PairedRate activeCompleted;      ///< active trials both experiments ran
    PairedRate passiveLostAtCorner;  ///< passive trials both ran
    /// Active trials both completed and recognised: named rightly by the paper's rule.
    PairedRate recognisedRaw;
    PairedRate paperResult;  ///< runs (seeds) where both have the paper's parts
};

/// Each part: its key in compare.json and compare_so_far.csv, its name in text and figures, and
/// where it sits in a PairedParts; in the order they are reported.
struct PairedPart {
    const char* key;
    const char* name;
    PairedRate PairedParts::*rate;
};
inline constexpr PairedPart kPairedParts[] = {
    {"active_completed", "active trials completed", &PairedParts::activeCompleted},
    {"passive_lost_at_a_corner", "passive trials lost at a corner",
     &PairedParts::passiveLostAtCorner},
    {"recognised_raw", "completed paths recognised (paper's rule)", &PairedParts::recognisedRaw},
    {"paper_result", "runs with the paper's result whole", &PairedParts::paperResult},
};

/// All a comparison takes from one seed's two runs, kept so that shards of a comparison run on
/// other machines merge into exactly what one run writes (docs/command-line.md).
struct SeedPairRecord {
    std::uint64_t seed = 0;
    /// "seed 3, a (name): ..." for each run that failed; then nothing else of the seed counts.
    std::vector<std::string> failedRuns;
    double robotTimeA_s = 0.0, robotTimeB_s = 0.0;
    int unpairedTrials = 0;
    struct Trial {
        PairedTrial pair;
        bool completedA = false, completedB = false;
        bool atCornerA = false, atCornerB = false;  ///< passive: stopped at a corner
        bool recognitionApplies = false;            ///< active, both completed and recognised
        bool namedRightA = false, namedRightB = false;
    };
    std::vector<Trial> trials;  ///< in the order experiment A runs them
    bool paperResultApplies = false, paperResultA = false, paperResultB = false;
};

/// The record of one seed: `a` and `b` are the two experiments' runs with that seed.
SeedPairRecord seedPairRecord(const RunResult& a, const RunResult& b);

struct PairedComparison : PairedParts {
    std::string nameA, nameB;
    int seeds = 0;
    /// The parts as they stood after each seed, in the order the seeds were added: how the
    /// differences settle.
    std::vector<PairedParts> soFar;
    /// Trials only one experiment has (a label, mode or repeat the other lacks); not compared.
    int unpairedTrials = 0;
    /// Seeds whose run failed in either experiment on a device or rig error: "seed 3, a: ...".
    /// Their trials are not compared (a failed run is no outcome of either experiment).
    std::vector<std::string> failedRuns;
    double robotTimeSumA_s = 0.0, robotTimeSumB_s = 0.0;  ///< whole runs
    double robotTimeDiffSquares = 0.0;                    ///< sum of (B - A)^2 per seed
    double meanRobotTimeA_s() const { return seeds ? robotTimeSumA_s / seeds : 0.0; }
    double meanRobotTimeB_s() const { return seeds ? robotTimeSumB_s / seeds : 0.0; }
    /// The standard deviation over seeds of B's robot time minus A's, per run (0 for fewer than
    /// two seeds).
    double robotTimeDifferenceSd_s() const;
    /// Every seed added, in the order added.
    std::vector<SeedPairRecord> records;
};

/// Adds one seed's record; `trials` (if given) gets each pair.
void addSeedRecord(PairedComparison& c, const SeedPairRecord& record,
                   std::vector<PairedTrial>* trials = nullptr);

/// Adds one seed: `a` and `b` are the two experiments' runs with that seed. Trials pair by mode,
/// label and repeat; `trials` (if given) gets each pair.
void addSeed(PairedComparison& c, const RunResult& a, const RunResult& b,
             std::vector<PairedTrial>* trials = nullptr);

/// Throws InputError if `a` and `b` share no trial (the same label and mode) to compare.
void checkComparable(const ExperimentSpec& a, const ExperimentSpec& b);

/// Runs `a` and `b` once per seed first..last, `jobs` seeds at once (forEachSeed: the results are
/// the same for any number), and compares them in seed order. With `outDir`, writes
/// compare.csv (a row per paired trial) and compare_so_far.csv (each part's comparison after each
/// seed, the table behind the figure's second panel), both appended as each seed finishes, and
/// compare.json (the comparison, written last). `seedDone` hears each seed's pairs and the
/// comparison so far; returning false stops after it. checkComparable before any run.
using ComparedSeed = std::function<bool(std::uint64_t seed, const std::vector<PairedTrial>& pairs,
                                        const PairedComparison& soFar)>;
PairedComparison comparePaired(const SimulatedRigs& rigs, const ExperimentSpec& a, const ExperimentSpec& b,
                               std::uint64_t first, std::uint64_t last, const std::string& outDir,
                               const ComparedSeed& seedDone = {}, int jobs = defaultSeedJobs());

Json pairedComparisonJson(const PairedComparison& c);

/// Starts <outDir>/compare.csv and compare_so_far.csv with their headers.
void startComparisonTables(std::optional<OutputFile>& table, std::optional<OutputFile>& soFar,
                           const std::string& outDir);
/// Appends the seed `c` added last: its pairs to compare.csv, each part so far to
/// compare_so_far.csv (a failed seed adds its parts unchanged, as it stood).
void appendComparedSeed(OutputFile& table, OutputFile& soFar, const PairedComparison& c,
                        const std::vector<PairedTrial>& pairs);

/// One trial of one seed as each of two experiments ran it: to see where a setting made them
/// part.
struct TrialPairRun {
    std::string nameA, nameB;
    std::uint64_t seed = 0;
    TrialRun a, b;
};

/// Runs `a` and `b` with `seed` and returns the trial both have as `mode`, `label` and repeat
/// `trial`, as each ran it: the same trial compare pairs. Throws InputError naming the trial if
/// either experiment lacks it.
TrialPairRun runTrialPair(const SimulatedRigs& rigs, const ExperimentSpec& a, const ExperimentSpec& b, std::uint64_t seed,
                          FollowingMode mode, const std::string& label, int trial);

/// The name a pair's table and figure take, e.g. "trial_pair_seed3_active_cross_2" (characters
/// of the label a file name should not hold become '_').
std::string trialPairFileStem(const TrialPairRun& pair);

/// Writes <outDir>/<trialPairFileStem>.csv: a row per tap of each side's trial, its side ("a" or
/// "b") and experiment name (quoted), then the columns of following_paths.csv (kTrialTapColumns).
/// Throws naming the file if it cannot be written whole.
void writeTrialPairTable(const TrialPairRun& pair, const std::string& outDir);

/// How a trial of a pair ended, as compare.csv and the Compare tab say it: "completed" or
/// "lost at a corner (reason)" or "lost away from corners (reason)", and the shape the paper's
/// rule named a completed path.
std::string trialOutcome(const TrialRun& t);
std::string namedPath(const TrialRun& t);
/// "<outcome>", or "<outcome>, named <shape>" for a path the paper's rule named.
std::string endedText(const std::string& outcome, const std::string& named);
inline std::string endedText(const TrialRun& t) {
    return endedText(trialOutcome(t), namedPath(t));
}

/// The comparison as lines of text: each outcome's rate in A and in B, the pairs where they
/// differ, the difference with its interval and McNemar's p.
std::vector<std::string> describeComparison(const PairedComparison& c);

}  // namespace activetouch
