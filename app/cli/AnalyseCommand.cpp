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

/// What was read from the recording and replayed, printed after the run.
void printReplayed(const RunResult& result, const RecordedRun& recorded,
                   const std::string& recordingPath, bool replay) {
    const ExperimentSpec& spec = result.spec;
    if (replay)
        std::printf(
            "%s: %zu recorded training and test taps and %d following taps over %d trials "
            "from %s replayed (%.0f s of recorded robot time)\n",
            spec.name.c_str(), result.taps.size(), recorded.followingTaps,
            static_cast<int>(recorded.trials.size()), recordingPath.c_str(), result.robotTime_s);
    else
        std::printf(
            "%s: %zu recorded taps from %s re-analysed (recorded over %.0f s of robot time)\n",
            spec.name.c_str(), result.taps.size(), recordingPath.c_str(), result.robotTime_s);
    if (!recorded.tapsCutOff.empty())
        std::printf(
            "the recording was cut short at the end, as by a run stopped while writing: %s; that "
            "tap is left out\n",
            recorded.tapsCutOff.c_str());
    if (!recorded.trialsCutOff.empty())
        std::printf("the following recording was cut short at the end: %s; that tap is left out\n",
                    recorded.trialsCutOff.c_str());
    for (const TrialRun& t : result.trials) {
        if (t.recordedTaps < 0) continue;
        if (t.result.end == TrialEnd::LeftRecording)
            std::printf("replayed %s %s trial %d: %s\n", modeName(t.result.mode), t.label.c_str(),
                        t.trial, t.result.detail.c_str());
        else
            std::printf("replayed %s %s trial %d: %zu of %d recorded taps retraced, %s\n",
                        modeName(t.result.mode), t.label.c_str(), t.trial, t.result.taps.size(),
                        t.recordedTaps, trialEndName(t.result.end));
    }
    if (!result.sweeps.compute.empty())
        std::printf(
            "sweep (c): %zu settings of bins and samples per tap measured on the recorded taps\n",
            result.sweeps.compute.size());
    if (!spec.sweeps.beliefThresholds.empty() || !spec.sweeps.followSteps_mm.empty())
        std::printf(
            "sweeps (a) and (b) take new taps and follow contours on simulated rigs: not run on a "
            "recording\n");
}

/// The recording, read whole before anything is written (the output may be where it lies).
RecordedRun readRecording(const std::string& path, const ExperimentSpec& spec, bool replay) {
    if (replay) return readRecordedRun(path, spec.classes);
    RecordedRun recorded;
    recorded.taps = readTapCsv(path, spec.classes, &recorded.tapsCutOff,
                               checkedRecordingBounds(path, &recorded.note));
    return recorded;
}

}  // namespace

/// analyse (recorded training and test taps) and replay (a run's whole recording, its trials
/// replayed as rigs).
int commandAnalyse(const std::vector<std::string>& args, int argc, char** argv, bool replay) {
    const char* command = replay ? "replay" : "analyse";
    const RunArguments parsed = parseRunArguments(args, command, {}, true, true);
    if (!parsed.error.empty()) return usageError(parsed.error);
    const auto start = std::chrono::steady_clock::now();
    const auto loaded = loadForRun(parsed.experimentPath);
    if (!loaded) return kBadInput;
    const ExperimentSpec& spec = *loaded;
    const std::string outDir =
        parsed.outDir.empty()
            ? (fs::path("results") / (spec.name + (replay ? "_replay" : "_analysis"))).string()
            : parsed.outDir;
    try {
        const RecordedRun recorded = readRecording(parsed.recordingPath, spec, replay);
        RunOptions options;
        options.simulated = &simulatedRigs();
        options.outDir = outDir;
        options.recordedTaps = &recorded.taps;
        options.recordedTrials = replay ? &recorded.trials : nullptr;
        options.recordingName = parsed.recordingPath;
        if (!recorded.note.empty()) std::fprintf(stderr, "caution: %s\n", recorded.note.c_str());
        // The folder is claimed once the recording has passed every check: a refused one
        // writes nothing.
        std::optional<RunFolderClaim> claimed;
        options.beforeWriting = [&] {
            claimed.emplace(outDir, command, spec.name, runFactsOf(spec, &recorded.taps),
                            parsed.replace);
        };
        const RunResult result = runExperiment(spec, options);
        const ArtefactTiming t = writeArtefacts(result, outDir, parsed.figures, argc, argv, start);
        printReplayed(result, recorded, parsed.recordingPath, replay);
        printReport(result, t.wall_s, t.figures_s, outDir);
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s failed: %s\n", replay ? "replay" : "analysis", e.what());
        return kRunFailed;
    }
}

}  // namespace activetouch::cli
