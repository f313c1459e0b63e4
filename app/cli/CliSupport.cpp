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

#include "app/cli/CommandLine.h"
#include "app/figures/ComparisonFigures.h"
#include "app/figures/FigureExport.h"
#include "app/figures/FollowingFigures.h"
#include "app/figures/SeedFigures.h"
#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedRates.h"
#include "core/analysis/SeedShards.h"
#include "core/analysis/SweepRates.h"
#include "core/experiment/Experiment.h"
#include "core/experiment/ReachCautions.h"
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

/// Set by Ctrl-C (SIGINT) or SIGTERM on devices: while connecting, the stage's origin search is
/// stopped; in the run, the run stops after the tap in flight, leaves the tapper retracted and
/// the stage still, and keeps every tap taken.
std::atomic<bool> gInterrupted{false};

static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void onInterrupt(int) {
    gInterrupted.store(true);
}

int usageError(const std::string& message) {
    std::fprintf(stderr, "activetouch-cli: %s\nRun 'activetouch-cli --help' for usage.\n",
                 message.c_str());
    return kBadInput;
}

/// Says, before any tap, what an experiment will run but cannot do well.
void printCautions(const ExperimentSpec& spec) {
    for (const std::string& c : untrainedEdgeCautions(spec))
        std::fprintf(stderr, "caution: %s\n", c.c_str());
    for (const std::string& c : unresolvedFeatureCautions(spec))
        std::fprintf(stderr, "caution: %s\n", c.c_str());
}

/// The experiment a run or seeds command takes, checked, its cautions printed; on bad input the
/// message is printed and nothing is returned.
std::optional<ExperimentSpec> loadForRun(const std::string& path) {
    try {
        ExperimentSpec spec = loadCheckedExperiment(path, true, simulatedRigs());
        printCautions(spec);
        return spec;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return std::nullopt;
    }
}

/// Refuses (printing why) a plan of `runs` runs of `spec` beyond the bounds, unless allowed;
/// `onRig`: its taps are taken on a rig, so its robot time is bounded too.
bool planAccepted(const ExperimentSpec& spec, double runs, bool allowed, bool onRig) {
    const RunPlan plan = planOf(spec).times(runs);
    const PlanProblem problem = planProblem(
        plan,
        runs > 1 ? std::to_string(static_cast<long long>(runs)) + " runs of the experiment"
                 : "the experiment",
        onRig);
    if (problem.empty() || allowed) return true;
    std::fprintf(stderr, "error: %s\n",
                 InputError::compose(spec.source, problem.place, problem.problem).c_str());
    return false;
}

/// Claims `outDir` for a run (printing why not); while it lives, the folder's run.json is
/// completed with the run's files whenever the command ends.
std::optional<RunFolderClaim> claimOrSay(const std::string& outDir, const char* command,
                                         const ExperimentSpec& spec, const RunFacts& facts,
                                         bool replace) {
    try {
        return std::optional<RunFolderClaim>(std::in_place, outDir, command, spec.name, facts,
                                             replace);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return std::nullopt;
    }
}

void setUpHeadlessDisplay() {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    const char* platform = std::getenv("QT_QPA_PLATFORM");
    if ((!display || !*display) && (!wayland || !*wayland) && (!platform || !*platform))
        setenv("QT_QPA_PLATFORM", "offscreen", 1);
}

double drawFigures(int argc, char** argv, const std::function<void()>& write) {
    const auto start = std::chrono::steady_clock::now();
    setUpHeadlessDisplay();
    QApplication app(argc, argv);
    write();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::optional<std::uint64_t> parseSeed(const std::string& v) {
    char* end = nullptr;
    const long long n = std::strtoll(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || n < 0 || n > 2147483647LL) return std::nullopt;
    return static_cast<std::uint64_t>(n);
}

/// `textOptions` maps each text option the command takes to what it needs, e.g. {"--rig", "a rig
/// file, e.g. rig.json"}.
RunArguments parseRunArguments(const std::vector<std::string>& args, const char* command,
                               const std::vector<std::string>& seedOptions, bool figuresOption,
                               bool takesRecording,
                               const std::map<std::string, std::string>& textOptions) {
    RunArguments r;
    auto fail = [&](const std::string& message) {
        r.error = message;
        return r;
    };
    const std::string name = command;
    CommandSyntax syntax;
    syntax.values.push_back({"--out", "a folder"});
    for (const std::string& o : seedOptions) syntax.values.push_back({o, "a whole number"});
    for (const auto& [o, what] : textOptions) syntax.values.push_back({o, what});
    syntax.flags.push_back("--replace");
    if (figuresOption) syntax.flags.push_back("--no-figures");
    if (name != "analyse" && name != "replay") syntax.flags.push_back("--allow-long-plan");
    const CommandLine line = parseCommandLine(syntax, args);
    if (!line.error.empty()) return fail(line.error);
    r.outDir = line.value("--out");
    for (const std::string& o : seedOptions) {
        if (!line.values.count(o)) continue;
        const std::string& v = line.values.at(o);
        const auto n = parseSeed(v);
        if (!n) return fail(o + " '" + v + "' is not a whole number between 0 and 2147483647");
        r.seeds[o] = *n;
    }
    for (const auto& [o, what] : textOptions)
        if (line.values.count(o)) r.texts[o] = line.values.at(o);
    r.figures = !line.has("--no-figures");
    r.replace = line.has("--replace");
    r.allowLongPlan = line.has("--allow-long-plan");
    const std::size_t wanted = takesRecording ? 2 : 1;
    if (line.positional.size() > wanted)
        return fail("unexpected argument '" + line.positional[wanted] + "'");
    if (!line.positional.empty()) r.experimentPath = line.positional[0];
    if (line.positional.size() > 1) r.recordingPath = line.positional[1];
    if (r.experimentPath.empty())
        return fail(std::string(command) +
                    " needs an experiment file, e.g. experiments/paper.json");
    if (takesRecording && r.recordingPath.empty())
        return fail(std::string(command) +
                    (std::string(command) == "replay"
                         ? " needs a run's folder after the experiment, e.g. results/paper"
                     : std::string(command) == "compare"
                         ? " needs a second experiment to compare with, e.g. "
                           "experiments/paper_kernel.json"
                         : " needs a recording of training and test taps after the experiment, "
                           "e.g. results/paper/data/taps.csv"));
    return r;
}

/// `example` is the command with a range, e.g. "seeds --from 1 --to 10".
SeedRange seedRangeOf(const RunArguments& parsed, const std::string& example) {
    SeedRange r;
    const std::string command = example.substr(0, example.find(' '));
    if (!parsed.seeds.count("--from") || !parsed.seeds.count("--to")) {
        r.error = command + " needs --from and --to, e.g. " + example.substr(command.size() + 1);
        return r;
    }
    r.first = parsed.seeds.at("--from");
    r.last = parsed.seeds.at("--to");
    if (r.first > r.last)
        r.error = "--from " + std::to_string(r.first) + " is after --to " + std::to_string(r.last) +
                  "; give the first seed first";
    r.jobs = defaultSeedJobs();
    if (const auto jobs = parsed.seeds.find("--jobs"); jobs != parsed.seeds.end()) {
        if (jobs->second < 1 || jobs->second > 1024)
            r.error = "--jobs " + std::to_string(jobs->second) +
                      " cannot run seeds; give how many seeds run at once, from 1 (one after "
                      "another) to 1024";
        r.jobs = static_cast<int>(std::min<std::uint64_t>(jobs->second, 1024));
    }
    if (const std::string text = parsed.text("--shard"); !text.empty() && r.error.empty()) {
        const auto read = parseShard(text, &r.error);
        if (read) r.shard = *read;
    }
    if (r.error.empty()) r.seeds = shardSeeds(r.first, r.last, r.shard);
    return r;
}

void printShardBlock(const SeedRange& range) {
    if (range.shard.count <= 1) return;
    std::printf(
        "\nshard %d/%d of seeds %llu-%llu: %s\n", range.shard.index, range.shard.count,
        static_cast<unsigned long long>(range.first), static_cast<unsigned long long>(range.last),
        range.seeds
            ? (std::to_string(range.seeds->first) + "-" + std::to_string(range.seeds->second))
                  .c_str()
            : "no seeds");
}

/// Writes a finished run's tables, its figures if asked, and last its summary.json.
ArtefactTiming writeArtefacts(const RunResult& result, const std::string& outDir, bool figures,
                              int argc, char** argv, std::chrono::steady_clock::time_point start,
                              double figureWidthMm) {
    if (!figures) return writeRunArtefacts(result, outDir, start);
    return writeRunArtefacts(result, outDir, start, [&] {
        return drawFigures(argc, argv, [&] {
            writeRunFigures(result, QString::fromStdString(outDir), figureWidthMm);
        });
    });
}

std::optional<double> figureWidthOf(const RunArguments& parsed, std::string& error) {
    const std::string text = parsed.text("--figure-width-mm");
    if (text.empty()) return 0.0;
    char* end = nullptr;
    const double width = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !(width >= kLeastFigureWidth_mm) ||
        !(width <= kMostFigureWidth_mm)) {
        error = "--figure-width-mm '" + text + "' is not a width from " +
                std::to_string(int(kLeastFigureWidth_mm)) + " to " +
                std::to_string(int(kMostFigureWidth_mm)) +
                " mm; give the journal's column width, e.g. 89 (single) or 178 (double)";
        return std::nullopt;
    }
    return width;
}

/// ", at any pose star turned 37.2 deg (truth 36.9)" for a recognised trial.
std::string anyPoseText(const TrialRun& t) {
    const PoseRecognition& p = t.poseRecognition;
    if (!t.recognised || !p.valid) return {};
    std::string text = ", at any pose " + p.predicted;
    if (p.best.symmetry == 0) return text + " (no turn to tell)";
    // The recovered turn shown beside the truth as the equivalent turn nearest it.
    const double period = 360.0 / p.best.symmetry;
    const double truth = std::fmod(std::fmod(t.rotationDeg, period) + period, period);
    double off = std::fmod(p.best.rotationDeg - truth, period);
    if (off > period / 2) off -= period;
    if (off < -period / 2) off += period;
    char buf[120];
    std::snprintf(buf, sizeof buf, " turned %.1f deg (truth %.1f)", truth + off, truth);
    return text + buf;
}

/// How a trial ended and what it measured, as a run's report gives it after "trial N: ".
void printTrialMeasures(const TrialRun& t) {
    std::printf(
        "%-38s %4zu taps, %6.0f s robot time, coverage %3.0f %%, contour distance mean %.2f max "
        "%.2f mm%s%s%s%s\n",
        trialEndName(t.result.end), t.result.taps.size(), t.result.robotTime_s,
        100.0 * t.result.coverage, t.result.meanContourDistance_mm, t.result.maxContourDistance_mm,
        t.recognised ? ", recognised as " : "", t.recognised ? t.recognition.predicted.c_str() : "",
        anyPoseText(t).c_str(),
        t.result.completed() ? "" : (", furthest " + describePlace(t.result.furthest)).c_str());
}

namespace {

/// The perception sweep's rows, when it ran.
void printPerceptionSweep(const SweepResults& sweeps) {
    const auto& c = sweeps.perceptionCalibration;
    if (!c.measured) return;
    std::printf(
        "sequential perception: one tap's belief on %d fresh taps has expected calibration "
        "error %.3f raw, %.3f %s (a perfectly calibrated belief would show %.3f)\n",
        c.taps, c.eceRaw, c.eceCalibrated, c.calibrated ? "calibrated" : "as used",
        c.eceIfCalibrated);
    const PerceptionSweepRow& one = sweeps.perceptionSingleTap;
    std::printf(
        "  single tap (the paper's)     %5.1f s per decision; edge angle error %5.2f deg "
        "(%5.2f-%5.2f), position error %.3f mm (%.3f-%.3f), class %.1f %%\n",
        one.meanRobotTime_s, one.angleError_deg, one.angle_deg.low, one.angle_deg.high,
        one.positionError_mm, one.position_mm.low, one.position_mm.high,
        100.0 * one.correctFraction);
    for (const auto& row : sweeps.perception)
        std::printf(
            "  belief %-8.6g %5.2f taps (%5.2f-%5.2f) %5.1f s per decision; edge angle error "
            "%5.2f deg (%5.2f-%5.2f), position error %.3f mm (%.3f-%.3f), class %.1f %%, "
            "plane %.0f %%, air %.0f %%\n",
            row.threshold, row.meanTaps, row.taps.low, row.taps.high, row.meanRobotTime_s,
            row.angleError_deg, row.angle_deg.low, row.angle_deg.high, row.positionError_mm,
            row.position_mm.low, row.position_mm.high, 100.0 * row.correctFraction,
            100.0 * row.planeRecognised, 100.0 * row.airRecognised);
}

/// Validation, the belief's calibration, the continuous percept and the noise floor.
void printValidation(const RunResult& result) {
    const auto& v = result.validation;
    std::printf(
        "validation: angle error %.2f deg, position error %.3f mm, class accuracy %.1f %%, "
        "%s\n",
        v.angleError_deg, v.positionError_mm, 100.0 * v.correctFraction,
        v.validRange.text().c_str());
    if (const BeliefCalibration& b = result.beliefCalibration; b.measured)
        std::printf(
            "belief calibration: expected calibration error %.3f raw, %.3f calibrated (%s: factor "
            "%.3g, floor %.3g; a perfectly calibrated belief would show %.3f on these %d held-out "
            "taps); evidence over repeated taps scaled by %.3g\n",
            b.eceRaw, b.eceCalibrated, b.method.c_str(), b.scaling.scale, b.scaling.floor,
            b.eceIfCalibrated, b.evaluationTaps, b.sequential.scale);
    if (v.continuousValidated)
        std::printf(
            "continuous percept: median angle error %.2f deg inside the valid range (%.2f deg "
            "over every edge position) on the test taps\n",
            v.continuousMedianAngleErrorInRange_deg, v.continuousMedianAngleError_deg);
    if (const std::string note = followingClassifierNote(result); !note.empty())
        std::printf("%s\n", note.c_str());
    if (const auto& m = result.measuredNoiseFloor)
        std::printf(
            "noise floor: %.1f counts (measured from %d taps that touched nothing; "
            "scene %.1f); classes whose ideal tap stays below it are air\n",
            result.noiseFloor_counts, m->taps, result.spec.scene.tap.noiseFloor);
    else
        std::printf(
            "noise floor: %.1f counts, the scene's (no class lies wholly in the air to "
            "measure it from)\n",
            result.noiseFloor_counts);
}

}  // namespace

/// What a run or an analysis found: validation, noise floor, trials, recognition, where it went.
void printReport(const RunResult& result, double wall, double figures_s,
                 const std::string& outDir) {
    const ExperimentSpec& spec = result.spec;
    printValidation(result);
    int labelWidth = 9;  // the columns line up whatever the trials are called
    for (const auto& t : result.trials) labelWidth = std::max(labelWidth, int(t.label.size()));
    for (const auto& t : result.trials) {
        std::printf("%-7s %-*s trial %d: ", modeName(t.result.mode), labelWidth, t.label.c_str(),
                    t.trial);
        printTrialMeasures(t);
    }
    if (result.pathAngleTaps > 0)
        std::printf(
            "continuous percept along the paths: median angle error %.2f deg against the true "
            "local edge (%d taps inside the valid range, away from corners)\n",
            result.pathMedianAngleError_deg, result.pathAngleTaps);
    if (!result.templates.empty())
        std::printf(
            "recognition: %.0f %% of %s paths by the paper's rule, templates at each shape's "
            "stated pose (smoothed histograms: %.0f %%)\n",
            100.0 * result.recognitionAccuracy, modeName(spec.recognition.ofMode),
            100.0 * result.recognitionAccuracySmoothed);
    if (!result.poseTemplates.empty())
        std::printf(
            "recognition at any pose: %.0f %% of %s paths; recovered turn off by %.2f deg, place "
            "by %.2f mm (medians over the paths named right)\n",
            100.0 * result.recognitionAccuracyAnyPose, modeName(spec.recognition.ofMode),
            result.medianRotationError_deg, result.medianPositionError_mm);
    printPerceptionSweep(result.sweeps);
    for (const std::string& line : describeRobustness(result.sweeps))
        std::printf("%s\n", line.c_str());
    if (const std::string b = describeBandit(result.sweeps.bandit, result.sweeps.following);
        !b.empty())
        std::printf("%s\n", b.c_str());
    std::printf("wall time %.3f s (figures %.3f s); results in %s\n", wall, figures_s,
                outDir.c_str());
}

/// A command over seeds whose runs all ended but some failed on a device or rig error exits 1,
/// saying so: such a run is no outcome of the experiment.
int failedRunsExit(int code, int failedRuns, const std::string& outDir, const char* where) {
    if (code != kOk || failedRuns == 0) return code;
    std::fprintf(stderr,
                 "%d run%s failed on a device or rig error (not counted as lost trials); see "
                 "%s/%s\n",
                 failedRuns, failedRuns == 1 ? "" : "s", outDir.c_str(), where);
    return kRunFailed;
}

/// What a seeds run or a merge prints as each seed finishes.
bool printSeedOutcome(const SeedOutcome& o) {
    std::printf("seed %llu: passive lost %d/%d, active completed %d/%d",
                static_cast<unsigned long long>(o.seed), o.passiveLost, o.passiveTrials,
                o.activeCompleted, o.activeTrials);
    if (o.recognition)
        std::printf(", recognised %d (smoothed %d) of %d", o.recognisedRaw(),
                    o.recognisedSmoothed(), o.recognitionTrials());
    std::printf("\n");
    if (o.failed())
        std::printf("    run failed, %d trials not run: %s\n", o.trialsNotRun,
                    o.runFailure.c_str());
    for (const auto& f : o.passiveShortfalls) std::printf("    %s\n", f.c_str());
    for (const auto& f : o.failures) std::printf("    %s\n", f.c_str());
    for (const auto& m : o.misnamed()) std::printf("    %s\n", m.c_str());
    std::fflush(stdout);
    return true;
}

/// The closing report of a seeds run or a merge: the rates over `first`..`last`.
void printSeedRates(const std::string& name, const SeedRates& rates, std::uint64_t first,
                    std::uint64_t last) {
    std::printf(
        "\n%s over %zu seeds (%llu-%llu; each seed one independent run in the 95 %% "
        "intervals, its trials sharing its training):\n",
        name.c_str(), rates.seeds.size(), static_cast<unsigned long long>(first),
        static_cast<unsigned long long>(last));
    for (const std::string& line : describeRates(rates)) std::printf("%s\n", line.c_str());
    if (const SweepRates sweeps = sweepRates(rates.seeds); !sweeps.empty()) {
        std::printf("\n");
        for (const std::string& line : describeSweepRates(sweeps))
            std::printf("%s\n", line.c_str());
    }
}

}  // namespace activetouch::cli
