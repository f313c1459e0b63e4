#include "app/cli/Commands.h"
#include "app/cli/CliSupport.h"

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

#include "app/figures/ComparisonFigures.h"
#include "app/figures/FigureExport.h"
#include "app/figures/FollowingFigures.h"
#include "app/figures/SeedFigures.h"
#include "core/run/ExperimentFiles.h"
#include "core/run/RunArtefacts.h"
#include "core/run/ExperimentRun.h"
#include "core/run/RecordedRuns.h"
#include "core/analysis/PairedComparison.h"
#include "core/run/RunFolder.h"
#include "core/analysis/SeedRates.h"
#include "core/analysis/SeedShards.h"
#include "core/experiment/Experiment.h"
#include "core/experiment/RunPlan.h"
#include "core/io/Csv.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "core/rig/Rig.h"
#include "devices/rigs/RigAssembly.h"
#include "devices/rigs/RigFile.h"
#include "devices/simulated/SimulatedWorld.h"

namespace activetouch::cli {

namespace fs = std::filesystem;

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
    const auto claimed = claimOrSay(outDir, "seeds", spec, runFactsOf(spec), parsed.replace);
    if (!claimed) return kBadInput;
    int failedRuns = 0;
    const int code = overSeeds(
        "run failed", outDir, "rates.csv", parsed.figures, range.jobs, argc, argv,
        [&] {
            const SeedRates rates =
                seeds ? runSeeds(simulatedRigs(), spec, seeds->first, seeds->second, outDir, printSeedOutcome,
                                 range.jobs)
                      : runSeeds(simulatedRigs(), spec, 1, 0, outDir);
            failedRuns = rates.runsFailed().count;
            // Every seed's whole outcome, so that shards merge into exactly one run's files.
            writeSeedShardFile(outDir, {spec.name, experimentFingerprint(experimentPath, spec),
                                        range.first, range.last, range.shard, rates.seeds});
            printShardBlock(range);
            printSeedRates(spec.name, rates, seeds ? seeds->first : range.first,
                           seeds ? seeds->second : range.first);
            return rates;
        },
        [&](const SeedRates& rates) {
            writeSeedFigures(rates, QString::fromStdString(spec.name),
                             QString::fromStdString(outDir));
        });
    return failedRunsExit(code, failedRuns, outDir, "rates.csv");
}

}  // namespace activetouch::cli
