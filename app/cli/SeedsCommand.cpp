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
#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedJournal.h"
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

/// A seeds run of this experiment, range and shard that was cut short in `outDir` (killed,
/// pre-empted or stopped): what its journal holds. Nothing where the folder holds no such run
/// (the claim then says what it holds) or --replace starts afresh.
std::optional<JournalResume> cutShortRun(const std::string& outDir, const SeedShardFile& run,
                                         const SeedRange& range, bool replace) {
    if (replace || !range.seeds || !holdsRun(outDir)) return std::nullopt;
    return readSeedJournal(outDir, run, range.seeds->first, range.seeds->second);
}

void printResume(const JournalResume& r) {
    const std::uint64_t done = r.outcomes.size();
    if (done == 0)
        std::printf("resuming a run cut short before its first seed: running seeds %llu-%llu\n",
                    static_cast<unsigned long long>(r.blockFirst),
                    static_cast<unsigned long long>(r.blockLast));
    else
        std::printf("resuming a run cut short: seeds %llu-%llu were done (from its journal), %s\n",
                    static_cast<unsigned long long>(r.blockFirst),
                    static_cast<unsigned long long>(r.blockFirst + done - 1),
                    r.blockFirst + done > r.blockLast
                        ? "none left to run"
                        : ("running " + std::to_string(r.blockFirst + done) + "-" +
                           std::to_string(r.blockLast))
                              .c_str());
    std::fflush(stdout);
}

}  // namespace

int commandSeeds(const std::vector<std::string>& args, int argc, char** argv) {
    const RunArguments parsed =
        parseRunArguments(args, "seeds", {"--from", "--to", "--jobs"}, true, false,
                          {{"--shard", "K/N, e.g. 2/3 for the second of three shards"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    const std::string& experimentPath = parsed.experimentPath;
    std::string outDir = parsed.outDir;
    const SeedRange range = seedRangeOf(parsed, "seeds --from 1 --to 10");
    if (!range.error.empty()) return usageError(range.error);
    const auto& seeds = range.seeds;  // this shard's block; none if it has no seed
    const auto loaded = loadForRun(experimentPath);
    if (!loaded) return kBadInput;
    const ExperimentSpec& spec = *loaded;
    const double runs = range.runs();
    if (!planAccepted(spec, runs, parsed.allowLongPlan)) return kBadInput;
    if (outDir.empty()) outDir = (fs::path("results") / (spec.name + "_seeds")).string();
    const SeedShardFile run{spec.name,   experimentFingerprint(experimentPath, spec),
                            range.first, range.last,
                            range.shard, {}};
    std::optional<JournalResume> resumed;
    try {
        resumed = cutShortRun(outDir, run, range, parsed.replace);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    }
    if (resumed) printResume(*resumed);
    const auto claimed =
        claimOrSay(outDir, "seeds", spec, runFactsOf(spec), parsed.replace || resumed);
    if (!claimed) return kBadInput;
    std::vector<SeedOutcome> before;  // the seeds a cut-short run finished, run no more
    if (resumed) before = std::move(resumed->outcomes);
    int failedRuns = 0;
    const int code = overSeeds(
        "run failed", outDir, "rates.csv", parsed.figures, range.jobs, argc, argv,
        [&] {
            if (!seeds) {
                const SeedRates rates = runSeeds(simulatedRigs(), spec, 1, 0, outDir);
                writeSeedShardFile(outDir, {run.experiment, run.fingerprint, range.first,
                                            range.last, range.shard, rates.seeds});
                printShardBlock(range);
                printSeedRates(spec.name, rates, range.first, range.first);
                return rates;
            }
            // Each seed's outcome journalled as it finishes: a run cut short resumes from there.
            SeedJournal journal(outDir, run, before);
            const SeedRates rates = runSeeds(
                simulatedRigs(), spec, seeds->first + before.size(), seeds->second, outDir,
                [&](const SeedOutcome& o) {
                    journal.append(o);
                    return printSeedOutcome(o);
                },
                range.jobs, before);
            failedRuns = rates.runsFailed().count;
            if (rates.seeds.size() == seeds->second - seeds->first + 1) journal.finish();
            // Every seed's whole outcome, so that shards merge into exactly one run's files.
            writeSeedShardFile(outDir, {run.experiment, run.fingerprint, range.first, range.last,
                                        range.shard, rates.seeds});
            printShardBlock(range);
            printSeedRates(spec.name, rates, seeds->first, seeds->second);
            return rates;
        },
        [&](const SeedRates& rates) {
            writeSeedFigures(rates, QString::fromStdString(spec.name),
                             QString::fromStdString(outDir));
        });
    return failedRunsExit(code, failedRuns, outDir, "rates.csv");
}

}  // namespace activetouch::cli
