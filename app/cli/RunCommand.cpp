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

/// Runs `spec` on the devices `rigConfig` names, into `result`; an exit code where it could not
/// connect or was stopped while connecting (nothing recorded), else nothing.
std::optional<int> runOnRig(const ExperimentSpec& spec, RunOptions& options, RigConfig& rigConfig,
                            char** argv, RunResult& result) {
    // The serial port and the YARP socket run on Qt's event machinery.
    int qtArgc = 1;
    QCoreApplication app(qtArgc, argv);
    auto model = std::make_shared<const FingertipContactModel>(spec.scene.fingertip);
    std::printf("connecting %s\n", rigConfig.describe().c_str());
    std::fflush(stdout);
    // From here Ctrl-C stops what the devices do (the origin search, then the run after the tap
    // in flight) instead of ending the process.
    const InterruptHandlers handlers;
    rigConfig.yamaha.stopOriginSearch = &gInterrupted;
    rigConfig.yarp.stop = &gInterrupted;
    std::unique_ptr<AssembledRig> assembled;
    try {
        assembled = std::make_unique<AssembledRig>(spec.scene, model, rigConfig);
    } catch (const RigError& e) {
        std::fprintf(stderr, "%s: %s\nNothing was recorded.\n",
                     gInterrupted ? "stopped while connecting" : "could not connect", e.what());
        return kRunFailed;
    }
    if (gInterrupted) {  // the rig lets the devices go as it ends
        std::fprintf(stderr, "stopped while connecting; nothing was recorded.\n");
        return kRunFailed;
    }
    const ConnectedRig connected{assembled->rig(), spec.scene.object, rigConfig.describe()};
    options.connected = &connected;
    StopFlag stop(gInterrupted);
    options.observer = &stop;
    result = runExperiment(spec, options);
    assembled->shutdown();
    return std::nullopt;
}

/// What the run took and how it ended, printed; its exit code.
int reportRun(const RunResult& result, const ArtefactTiming& t, bool onRig,
              const std::string& outDir) {
    const ExperimentSpec& spec = result.spec;
    if (onRig) {
        std::size_t taps = result.taps.size();
        for (const auto& trial : result.trials) taps += trial.result.taps.size();
        std::printf("%s: %zu taps on %s, %.0f s of robot time\n", spec.name.c_str(), taps,
                    result.rig.c_str(), result.robotTime_s);
    } else {
        std::printf("%s (seed %llu): %zu taps simulated, %.0f s of robot time\n", spec.name.c_str(),
                    static_cast<unsigned long long>(spec.scene.seed),
                    static_cast<std::size_t>(result.tapsSimulated), result.robotTime_s);
    }
    printReport(result, t.wall_s, t.figures_s, outDir);
    if (result.cancelled) {
        std::fprintf(stderr, "stopped before the end; every tap taken is in %s/data.\n",
                     outDir.c_str());
        return kRunFailed;
    }
    if (!result.failure.empty()) {
        std::fprintf(stderr, "run failed: %s\nEvery tap taken so far is in %s/data.\n",
                     result.failure.c_str(), outDir.c_str());
        return kRunFailed;
    }
    return kOk;
}

/// The rig file's devices, checked before anything connects; nothing without --rig.
std::optional<RigConfig> rigOf(const RunArguments& parsed, const ExperimentSpec& spec) {
    const std::string rigPath = parsed.text("--rig");
    if (rigPath.empty()) return std::nullopt;
    RigConfig config = readRigFile(rigPath, spec.scene);
    checkRunnableOn(spec, spec.scene.object);
    return config;
}

}  // namespace

int commandRun(const std::vector<std::string>& args, int argc, char** argv) {
    const RunArguments parsed =
        parseRunArguments(args, "run", {"--seed"}, true, false,
                          {{"--rig", "a rig file, e.g. rig.json"},
                           {"--figure-width-mm", "a width in mm, e.g. 89 for a single column"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    std::string widthError;
    const std::optional<double> figureWidth = figureWidthOf(parsed, widthError);
    if (!figureWidth) return usageError(widthError);
    std::string outDir = parsed.outDir;
    std::optional<std::uint64_t> seed;
    if (parsed.seeds.count("--seed")) seed = parsed.seeds.at("--seed");
    const auto start = std::chrono::steady_clock::now();
    const auto loaded = loadForRun(parsed.experimentPath);
    if (!loaded) return kBadInput;
    const ExperimentSpec& spec = *loaded;
    std::optional<RigConfig> rigConfig;
    try {
        rigConfig = rigOf(parsed, spec);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    }
    if (!planAccepted(spec, 1, parsed.allowLongPlan, rigConfig.has_value())) return kBadInput;
    if (outDir.empty()) outDir = (fs::path("results") / spec.name).string();
    const auto claimed = claimOrSay(outDir, "run", spec, runFactsOf(spec), parsed.replace);
    if (!claimed) return kBadInput;
    try {
        RunResult result;
        RunOptions options;
        options.simulated = &simulatedRigs();
        options.outDir = outDir;
        options.seed = seed;
        if (rigConfig) {
            if (const auto failed = runOnRig(spec, options, *rigConfig, argv, result))
                return *failed;
        } else {
            // Ctrl-C stops after the tap in flight, as on a rig, keeping every tap taken.
            const InterruptHandlers handlers;
            StopFlag stop(gInterrupted);
            options.observer = &stop;
            result = runExperiment(spec, options);
        }
        const ArtefactTiming t =
            writeArtefacts(result, outDir, parsed.figures, argc, argv, start, *figureWidth);
        return reportRun(result, t, rigConfig.has_value(), outDir);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    } catch (const RigError& e) {
        std::fprintf(stderr, "run failed: %s\nEvery tap taken so far is in %s/data.\n", e.what(),
                     outDir.c_str());
        return kRunFailed;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "run failed: %s\nEvery tap taken so far is in %s/data.\n", e.what(),
                     outDir.c_str());
        return kRunFailed;
    }
}

}  // namespace activetouch::cli
