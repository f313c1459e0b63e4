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
#include "app/cli/CommandLine.h"
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

/// A refusal of shards to run again, with a line a script can read: "rerun shards: 3,7".
int refuseShards(const ShardsToRerun& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    std::string list;
    for (const int k : e.shards()) {
        if (!list.empty()) list += ',';
        list += std::to_string(k);
    }
    std::fprintf(stderr, "rerun shards: %s\n", list.c_str());
    return kBadInput;
}

/// merge over the folders of a compare run's shards.
int mergeComparisons(const std::vector<std::string>& folders, const std::string& outDir,
                     bool figures, bool replace, int argc, char** argv) {
    ComparisonShardFile merged;
    try {
        merged = mergeComparisonShards(folders);
    } catch (const ShardsToRerun& e) {
        return refuseShards(e);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    }
    ExperimentSpec named;
    named.name = merged.nameA;
    const auto claimed = claimOrSay(outDir, "merge", named, RunFacts{}, replace);
    if (!claimed) return kBadInput;
    int failedRuns = 0;
    const int code = overSeeds(
        "merge failed", outDir, "compare.csv", figures, 1, argc, argv,
        [&] {
            const PairedComparison c = writeMergedComparison(merged, outDir);
            failedRuns = static_cast<int>(c.failedRuns.size());
            std::printf("merged %zu shard folders: %zu seeds\n\n", folders.size(),
                        merged.records.size());
            for (const std::string& line : describeComparison(c)) std::printf("%s\n", line.c_str());
            return c;
        },
        [&](const PairedComparison& c) {
            writeComparisonFigures(c, QString::fromStdString(outDir));
        });
    return failedRunsExit(code, failedRuns, outDir, "compare.json");
}

}  // namespace

int commandMerge(const std::vector<std::string>& args, int argc, char** argv) {
    const CommandLine line =
        parseCommandLine({{{"--out", "a folder"}}, {"--no-figures", "--replace"}}, args);
    if (!line.error.empty()) return usageError(line.error);
    const std::vector<std::string>& folders = line.positional;
    const std::string outDir = line.value("--out");
    const bool figures = !line.has("--no-figures"), replace = line.has("--replace");
    if (folders.empty())
        return usageError("merge needs the folders of the shards, e.g. merge S1 S2 S3 --out M");
    if (outDir.empty()) return usageError("merge needs --out, the folder to write");
    std::size_t comparisons = 0;
    for (const std::string& f : folders) comparisons += holdsComparisonShard(f);
    if (comparisons > 0 && comparisons < folders.size())
        return usageError("merge takes the shards of one seeds run or of one compare run; " +
                          std::to_string(comparisons) + " of the " +
                          std::to_string(folders.size()) + " folders hold a comparison");
    if (comparisons > 0) return mergeComparisons(folders, outDir, figures, replace, argc, argv);
    SeedShardFile merged;
    try {
        merged = mergeSeedShards(folders);
    } catch (const ShardsToRerun& e) {
        return refuseShards(e);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    }
    ExperimentSpec named;
    named.name = merged.experiment;
    RunFacts facts;
    const auto claimed = claimOrSay(outDir, "merge", named, facts, replace);
    if (!claimed) return kBadInput;
    int failedRuns = 0;
    const int code = overSeeds(
        "merge failed", outDir, "rates.csv", figures, 1, argc, argv,
        [&] {
            const SeedRates rates = writeMergedSeeds(merged, outDir);
            failedRuns = rates.runsFailed().count;
            std::printf("merged %zu shard folders: %zu seeds\n", folders.size(),
                        merged.outcomes.size());
            printSeedRates(merged.experiment, rates, merged.first, merged.last);
            return rates;
        },
        [&](const SeedRates& rates) {
            writeSeedFigures(rates, QString::fromStdString(merged.experiment),
                             QString::fromStdString(outDir));
        });
    return failedRunsExit(code, failedRuns, outDir, "rates.csv");
}

}  // namespace activetouch::cli
