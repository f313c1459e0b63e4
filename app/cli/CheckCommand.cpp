#include "app/cli/Commands.h"
#include "app/cli/CliSupport.h"
#include "app/cli/CommandLine.h"

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

namespace {

/// check on a recording: a tap recording (data/taps.csv) or a following recording
/// (data/following_taps.csv), told apart by their header; every row, column and value checked,
/// against the run's run.json where it has one, else against `experiment` or the paper's
/// fingertip.
int checkRecording(const std::string& file, const std::string& experiment) {
    try {
        std::string note;
        RecordingBounds bounds = checkedRecordingBounds(file, &note);
        ClassSet classes;
        if (!experiment.empty()) {
            const ExperimentSpec spec = loadCheckedExperiment(experiment, false, simulatedRigs());
            classes = spec.classes;
            bounds.taxels = static_cast<int>(spec.scene.fingertip.taxels.size());
            bounds.taxelsFrom = "the fingertip of " + experiment;
        } else if (bounds.taxels <= 0) {
            // Nothing says which fingertip took it: held to the paper's.
            bounds.taxels = kFingertipTaxels;
            bounds.taxelsFrom =
                "the paper's fingertip (there is no run.json beside the recording; give "
                "--experiment with the experiment it was taken with to check it against "
                "that one's)";
        }
        if (!note.empty()) std::fprintf(stderr, "caution: %s\n", note.c_str());
        std::ifstream in = openRecording(file);
        std::string header(17, '\0');
        in.read(header.data(), static_cast<std::streamsize>(header.size()));
        header.resize(static_cast<std::size_t>(in.gcount()));
        const bool known = bounds.samplesPerTap > 0;
        auto unconfirmed = [&](int taps) {
            return known || taps > 1 ? ""
                                     : "; with one tap and no run.json beside it, nothing "
                                       "shows whether that tap is whole";
        };
        if (header.rfind("shape,mode,trial,", 0) == 0) {
            const auto c = checkFollowingRecording(file, bounds);
            std::printf("%s: ok (%d taps over %d trials, %d samples each)%s%s%s\n",
                        file.c_str(), c.taps, c.trials, c.samplesPerTap,
                        c.cutOff.empty() ? ""
                                         : "; cut short at the end, as by a run "
                                           "stopped while writing: ",
                        c.cutOff.c_str(), unconfirmed(c.taps));
            return kOk;
        }
        std::string cut;
        const auto taps = readTapCsv(file, classes, &cut, bounds);
        std::printf("%s: ok (%zu taps, %d samples each)%s%s%s\n", file.c_str(), taps.size(),
                    taps.front().record.tap.sampleCount(),
                    cut.empty() ? ""
                                : "; cut short at the end, as by a run stopped while "
                                  "writing: ",
                    cut.c_str(), unconfirmed(static_cast<int>(taps.size())));
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    }
}

}  // namespace

int commandCheck(const std::vector<std::string>& argsIn) {
    const CommandLine line = parseCommandLine(
        {{{"--experiment", "the experiment the recording was taken with"}}, {"--allow-long-plan"}},
        argsIn);
    if (!line.error.empty()) return usageError(line.error);
    const std::vector<std::string>& args = line.positional;
    const bool allowLongPlan = line.has("--allow-long-plan");
    if (args.size() != 1) return usageError("check takes exactly one file");
    if (line.values.count("--experiment") && args[0].find(".csv") == std::string::npos)
        return usageError("--experiment goes with a recording (a .csv file) to check against it");
    const std::string& file = args[0];
    if (file.size() > 4 && file.substr(file.size() - 4) == ".csv")
        return checkRecording(file, line.value("--experiment"));
    try {
        if (const Json j = readJsonFile(file); looksLikeRigFile(j)) {
            // The stage's soft limits come from the experiment's scene at run time.
            const RigConfig rig = parseRigFile(j, file, SceneSpec{});
            std::printf("%s: ok (rig: %s)\n", file.c_str(), rig.describe().c_str());
            return kOk;
        }
        const ExperimentSpec spec = loadCheckedExperiment(file, false, simulatedRigs());
        const bool experiment = !spec.name.empty();
        if (experiment && !planAccepted(spec, 1, allowLongPlan)) return kBadInput;
        std::printf("%s: ok (%s; object %s, %zu effect%s listed)\n", file.c_str(),
                    experiment ? ("experiment '" + spec.name + "'").c_str() : "scene",
                    spec.scene.object.shape.c_str(), spec.scene.effects.size(),
                    spec.scene.effects.size() == 1 ? "" : "s");
        if (experiment) {
            const RunPlan plan = planOf(spec);
            std::printf("plan: %s\n", planText(plan).c_str());
            if (!planProblem(plan, "the experiment", true).empty())
                std::fprintf(stderr,
                             "caution: on a real rig this plan is beyond the %.0f h a run may take "
                             "there (run --rig refuses it without --allow-long-plan)\n",
                             kMaxPlannedRobotTime_s / 3600);
        }
        std::fflush(stdout);
        printCautions(spec);
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s: %s\n", file.c_str(), e.what());
        return kBadInput;
    }
}

}  // namespace activetouch::cli
