#include <QApplication>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "app/cli/CliSupport.h"
#include "app/cli/Commands.h"
#include "app/figures/ComparisonFigures.h"
#include "app/figures/FigureExport.h"
#include "app/figures/FollowingFigures.h"
#include "app/figures/SeedFigures.h"
#include "core/analysis/ComparisonShards.h"
#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedRates.h"
#include "core/analysis/SeedShards.h"
#include "core/experiment/Experiment.h"
#include "core/experiment/RunPlan.h"
#include "core/io/Csv.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "core/rig/Rig.h"
#include "core/run/ExperimentFiles.h"
#include "core/run/ExperimentRun.h"
#include "core/run/RecordedRuns.h"
#include "core/run/RunArtefacts.h"
#include "core/run/RunFolder.h"
#include "devices/rigs/RigAssembly.h"
#include "devices/rigs/RigFile.h"
#include "devices/simulated/SimulatedWorld.h"

namespace activetouch::cli {

namespace fs = std::filesystem;

namespace {

/// One trial of one seed, named as the first four columns of a compare.csv row name it.
struct TrialRef {
    std::uint64_t seed = 0;
    FollowingMode mode = FollowingMode::Active;
    std::string label;
    int trial = 0;
};

/// Reads "seed,mode,label,trial" (e.g. 3,active,cross,2; the label may be quoted, as compare.csv
/// quotes it); an error is the message to print.
std::variant<TrialRef, std::string> parseTrialRef(const std::string& text) {
    std::vector<std::string> fields = splitCsvLine(text);
    for (std::string& f : fields) {
        f.erase(0, f.find_first_not_of(' '));
        f.erase(f.find_last_not_of(' ') + 1);
    }
    const std::string form =
        "; give seed,mode,label,trial as the first four columns of a compare.csv row, e.g. "
        "3,active,cross,2";
    if (fields.size() != 4)
        return "--show '" + text + "' has " + std::to_string(fields.size()) + " field" +
               (fields.size() == 1 ? "" : "s") + form;
    TrialRef ref;
    const auto seed = parseSeed(fields[0]);
    if (!seed) return "--show: seed '" + fields[0] + "' is not a whole number" + form;
    ref.seed = *seed;
    const auto mode = modeNamed(fields[1]);
    if (!mode) return "--show: mode '" + fields[1] + "' is neither active nor passive" + form;
    ref.mode = *mode;
    ref.label = fields[2];
    if (ref.label.size() >= 2 && ref.label.front() == '"' && ref.label.back() == '"')
        ref.label = ref.label.substr(1, ref.label.size() - 2);
    if (ref.label.empty()) return "--show: the label is empty" + form;
    const auto trial = parseSeed(fields[3]);
    if (!trial || *trial < 1 || *trial > 1000)
        return "--show: trial '" + fields[3] + "' is not a repeat number from 1" + form;
    ref.trial = static_cast<int>(*trial);
    return ref;
}

/// compare --show: runs one seed in both experiments and shows one trial as each ran it, as a
/// table and a figure in `outDir`.
int showTrialPair(const ExperimentSpec& a, const ExperimentSpec& b, const TrialRef& ref,
                  const std::string& outDir, bool figures, int argc, char** argv) {
    try {
        const auto start = std::chrono::steady_clock::now();
        const TrialPairRun pair =
            runTrialPair(simulatedRigs(), a, b, ref.seed, ref.mode, ref.label, ref.trial);
        const int nameWidth = int(std::max(pair.nameA.size(), pair.nameB.size()));
        std::printf("seed %llu, %s trial %d of %s, as each experiment ran it:\n",
                    static_cast<unsigned long long>(ref.seed), modeName(ref.mode), ref.trial,
                    ref.label.c_str());
        for (const auto& [side, name, run] :
             {std::tuple{"a", &pair.nameA, &pair.a}, std::tuple{"b", &pair.nameB, &pair.b}}) {
            std::printf("%s %-*s  ", side, nameWidth, name->c_str());
            printTrialMeasures(*run);
        }
        std::printf("a %s; b %s\n", endedText(pair.a).c_str(), endedText(pair.b).c_str());
        std::fflush(stdout);
        writeTrialPairTable(pair, outDir);
        double figures_s = 0.0;
        if (figures)
            figures_s = drawFigures(
                argc, argv, [&] { writeTrialPairFigures(pair, QString::fromStdString(outDir)); });
        std::printf("wall time %.1f s (figures %.1f s); results in %s (%s.*)\n",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                    figures_s, outDir.c_str(), trialPairFileStem(pair).c_str());
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "compare failed: %s\n", e.what());
        return kRunFailed;
    }
}

/// One seed's paired trials as they come, the ones that ended differently named.
bool printSeedPairs(std::uint64_t seed, const std::vector<PairedTrial>& pairs,
                    const PairedComparison&) {
    int differ = 0;
    for (const PairedTrial& p : pairs) differ += p.differs();
    std::printf("seed %llu: %zu trials paired, %d ended differently\n",
                static_cast<unsigned long long>(seed), pairs.size(), differ);
    for (const PairedTrial& p : pairs)
        if (p.differs())
            std::printf("    %s %s trial %d: a %s, b %s\n", modeName(p.mode), p.label.c_str(),
                        p.trial, endedText(p.outcomeA, p.namedA).c_str(),
                        endedText(p.outcomeB, p.namedB).c_str());
    std::fflush(stdout);
    return true;
}

/// --show's trial, or the seed range: a usage error where they are mixed.
std::optional<std::string> readShowOrRange(const RunArguments& parsed, std::optional<TrialRef>& ref,
                                           SeedRange& range) {
    const std::string show = parsed.text("--show");
    if (show.empty()) {
        range = seedRangeOf(parsed, "compare --from 1 --to 100");
        if (!range.error.empty()) return range.error;
        return std::nullopt;
    }
    if (parsed.seeds.count("--from") || parsed.seeds.count("--to") || parsed.seeds.count("--jobs"))
        return "--show runs the one seed it names; leave out --from, --to and --jobs";
    auto read = parseTrialRef(show);
    if (auto* error = std::get_if<std::string>(&read)) return *error;
    ref = std::get<TrialRef>(read);
    if (!parsed.text("--shard").empty())
        return "--show runs the one seed it names; leave out --shard";
    return std::nullopt;
}

}  // namespace

int commandCompare(const std::vector<std::string>& args, int argc, char** argv) {
    const RunArguments parsed =
        parseRunArguments(args, "compare", {"--from", "--to", "--jobs"}, true, true,
                          {{"--show", "a trial: seed,mode,label,trial, e.g. 3,active,cross,2"},
                           {"--shard", "K/N, e.g. 2/3 for the second of three shards"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    std::optional<TrialRef> ref;
    SeedRange range;
    if (const auto error = readShowOrRange(parsed, ref, range)) return usageError(*error);
    const auto& seeds = range.seeds;  // this shard's block; none if it has no seed
    const auto a = loadForRun(parsed.experimentPath);
    if (!a) return kBadInput;
    const auto b = loadForRun(parsed.recordingPath);
    if (!b) return kBadInput;
    std::string outDir = parsed.outDir;
    if (outDir.empty()) outDir = (fs::path("results") / (a->name + "_vs_" + b->name)).string();
    // --show adds a trial's table and figure beside a comparison's files, as the window does.
    if (ref) return showTrialPair(*a, *b, *ref, outDir, parsed.figures, argc, argv);
    try {
        checkComparable(*a, *b);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    }
    const double runs = range.runs();
    if (!planAccepted(*a, runs, parsed.allowLongPlan) ||
        !planAccepted(*b, runs, parsed.allowLongPlan))
        return kBadInput;
    const auto claimed = claimOrSay(outDir, "compare", *a, runFactsOf(*a), parsed.replace);
    if (!claimed) return kBadInput;
    int failedRuns = 0;
    const int code = overSeeds(
        "compare failed", outDir, "compare.csv", parsed.figures, range.jobs, argc, argv,
        [&] {
            const PairedComparison c =
                comparePaired(simulatedRigs(), *a, *b, seeds ? seeds->first : 1,
                              seeds ? seeds->second : 0, outDir, printSeedPairs, range.jobs);
            // Every seed's record, so that shards merge into exactly one comparison's files.
            writeComparisonShardFile(outDir,
                                     {a->name, b->name,
                                      experimentFingerprint(parsed.experimentPath, *a) + "+" +
                                          experimentFingerprint(parsed.recordingPath, *b),
                                      range.first, range.last, range.shard, c.records});
            printShardBlock(range);
            std::printf("\n");
            for (const std::string& line : describeComparison(c)) std::printf("%s\n", line.c_str());
            failedRuns = static_cast<int>(c.failedRuns.size());
            return c;
        },
        [&](const PairedComparison& c) {
            writeComparisonFigures(c, QString::fromStdString(outDir));
        });
    return failedRunsExit(code, failedRuns, outDir, "compare.json");
}

}  // namespace activetouch::cli
