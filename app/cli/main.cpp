// activetouch-cli: the headless runner (docs/design.md §5).
//   activetouch-cli run <experiment.json> [--out <dir>] [--seed N] [--rig <rig>] [--no-figures]
//   activetouch-cli seeds <experiment.json> --from A --to B [--out <dir>] [--no-figures]
//   activetouch-cli analyse <experiment.json> <taps.csv> [--out <dir>] [--no-figures]
//   activetouch-cli replay <experiment.json> <run folder> [--out <dir>] [--no-figures]
//   activetouch-cli check <file.json | taps.csv | following_taps.csv>
// Exit codes: 0 ok, 1 the run failed, 2 bad input.
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
#include "core/run/PairedComparison.h"
#include "core/run/RunFolder.h"
#include "core/run/SeedRates.h"
#include "core/run/SeedShards.h"
#include "core/experiment/Experiment.h"
#include "core/experiment/RunPlan.h"
#include "core/io/Csv.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "core/rig/Rig.h"
#include "devices/rigs/RigAssembly.h"
#include "devices/rigs/RigFile.h"
#include "devices/simulated/SimulatedWorld.h"

using namespace activetouch;
namespace fs = std::filesystem;

namespace {

constexpr int kOk = 0, kRunFailed = 1, kBadInput = 2;

/// Set by Ctrl-C (SIGINT) or SIGTERM on devices: while connecting, the stage's origin search is
/// stopped; in the run, the run stops after the tap in flight, leaves the tapper retracted and
/// the stage still, and keeps every tap taken.
std::atomic<bool> gInterrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);
extern "C" void onInterrupt(int) {
    gInterrupted.store(true);
}

/// SIGINT and SIGTERM set gInterrupted while this lives.
struct InterruptHandlers {
    InterruptHandlers() {
        std::signal(SIGINT, onInterrupt);
        std::signal(SIGTERM, onInterrupt);
    }
    ~InterruptHandlers() {
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
    }
    InterruptHandlers(const InterruptHandlers&) = delete;
    InterruptHandlers& operator=(const InterruptHandlers&) = delete;
};

void printHelp() {
    std::printf(
        "activetouch-cli - ActiveTouch Workbench headless runner\n\n"
        "Usage:\n"
        "  activetouch-cli run <experiment.json> [--out <dir>] [--seed N] [--rig <rig.json>]\n"
        "                      [--no-figures]\n"
        "      Runs the experiment on the simulated rig and writes <dir>/summary.json,\n"
        "      <dir>/data/*.csv (every tap, appended as it is taken; every table behind a figure)\n"
        "      and <dir>/figures/*.{png,pdf,svg}. --out defaults to results/<experiment name>.\n"
        "      --seed overrides the experiment's seed (one seed = one whole run).\n"
        "      --rig takes the taps on the devices a rig file names instead (the Yamaha stage,\n"
        "      the NXT tapper with the fingertip over YARP, or a mix with simulated ones; see\n"
        "      docs/real-rig.md): the scene's object must be the one mounted. Ctrl-C stops after the\n"
        "      tap in flight, keeping every tap taken (while connecting, it stops the stage's\n"
        "      origin search).\n"
        "  activetouch-cli seeds <experiment.json> --from A --to B [--jobs N] [--out <dir>]\n"
        "                        [--no-figures]\n"
        "      Runs the experiment once per seed A..B (each a whole run: its own data sets,\n"
        "      training, valid range and trials) and reports the rates with 95 %% intervals:\n"
        "      passive trials lost (and lost at a corner), active trials completed (and per\n"
        "      trial label, and per valid range the runs picked), where the trials that did\n"
        "      not complete got furthest, the convex and concave corners each mode got round,\n"
        "      active paths recognised by both rules (and which shapes each misnamed as\n"
        "      which), runs with the paper's result whole. Writes <dir>/rates.csv (a row per\n"
        "      seed, appended as each finishes), <dir>/rates.json (with the recognition\n"
        "      confusion) and <dir>/figures/seed_rates.{png,pdf,svg} (each seed's outcome and\n"
        "      the rates so far with their intervals). --out defaults to\n"
        "      results/<experiment name>_seeds. --jobs runs N seeds at once (default: one per\n"
        "      core); every row and rate is the same for any N, reported in seed order.\n"
        "  activetouch-cli seeds <experiment.json> --from A --to B --shard K/N [...]\n"
        "      Runs only the K-th of N contiguous blocks of seeds A..B (for sweeps split across\n"
        "      machines); its folder keeps every seed's outcome in seed_outcomes.json.\n"
        "  activetouch-cli merge <folder>... --out <dir> [--no-figures]\n"
        "      Merges the folders of every shard of one seeds sweep into what one seeds run over\n"
        "      the whole range writes (rates.csv, rates.json, figures); refuses shards that\n"
        "      overlap, leave seeds out, or ran other settings, naming the seeds and folders.\n"
        "  activetouch-cli compare <a.json> <b.json> --from A --to B [--jobs N] [--out <dir>]\n"
        "                          [--no-figures]\n"
        "      Runs both experiments once per seed A..B and compares them trial by trial: a\n"
        "      seed gives both the same data sets and the same noise on each trial, so where\n"
        "      they differ in a setting, the trials whose outcomes differ show its effect.\n"
        "      Prints each outcome's rate in a and in b, the trials only one completed (or\n"
        "      lost at a corner, or recognised), the difference with its 95 %% interval and\n"
        "      McNemar's exact p, and the robot time per run. Writes <dir>/compare.csv (a row\n"
        "      per paired trial) and <dir>/compare_so_far.csv (each part's comparison after\n"
        "      each seed), both appended as each seed finishes, <dir>/compare.json and\n"
        "      <dir>/figures/compare.{png,pdf,svg} (each difference with its interval, and how\n"
        "      it settled seed by seed).\n"
        "      --out defaults to results/<a>_vs_<b>; --jobs as for seeds.\n"
        "  activetouch-cli compare <a.json> <b.json> --show SEED,MODE,LABEL,TRIAL [--out <dir>]\n"
        "                          [--no-figures]\n"
        "      Runs that seed in both experiments and shows that trial (as the first four\n"
        "      columns of a compare.csv row name it, e.g. 3,active,cross,2) as each ran it:\n"
        "      prints how each ended and what it measured, and writes\n"
        "      <dir>/trial_pair_seed<S>_<mode>_<label>_<trial>.csv (both paths, tap by tap)\n"
        "      and the same name under <dir>/figures as .png, .pdf and .svg (the object, both\n"
        "      paths with their taps, where a lost trial ended and how far it got).\n"
        "  activetouch-cli analyse <experiment.json> <taps.csv> [--out <dir>] [--no-figures]\n"
        "      Re-analyses recorded training and test taps (a run's data/taps.csv, from the\n"
        "      simulated or the real rig) with the experiment's classes, classifier, training\n"
        "      and validation settings: trains, validates and writes summary.json, the tables\n"
        "      and Figures 5 and 6. --out defaults to results/<experiment name>_analysis.\n"
        "  activetouch-cli replay <experiment.json> <run folder> [--out <dir>] [--no-figures]\n"
        "      Replays a run's recording (<run folder>/data/taps.csv and following_taps.csv,\n"
        "      from the simulated or the real rig) as a rig: trains and validates on the\n"
        "      recorded taps, then runs every trial of the experiment, served the recorded tap\n"
        "      wherever the recorded run tapped. With the run's own settings every trial\n"
        "      retraces its recording; with others, each trial says at which tap it decided\n"
        "      otherwise and left the recording. --out defaults to\n"
        "      results/<experiment name>_replay.\n"
        "  activetouch-cli check <file.json | taps.csv | following_taps.csv>\n"
        "                        [--allow-long-plan]\n"
        "      Validates an experiment (and prints its plan: taps and robot time), a scene,\n"
        "      a rig file or a recording (training taps,\n"
        "      or following taps: a run stopped while writing leaves every finished tap whole\n"
        "      and the cut is reported) and says what is wrong, if anything.\n"
        "  activetouch-cli --help\n\n"
        "Every command that writes a folder refuses one that already holds a run (its run.json,\n"
        "summary, tables or data) unless given --replace, which removes that run's files first;\n"
        "files of yours in the folder are left alone. run, seeds and compare refuse a plan\n"
        "beyond 10,000,000 taps, 24 h of robot time or 2 GiB of taps held in memory unless\n"
        "given --allow-long-plan; check prints the plan. Limits: docs/limits.md.\n\n"
        "Exit codes: 0 ok, 1 the run failed, 2 bad input (the message names the file, the place "
        "and the problem).\n");
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
bool planAccepted(const ExperimentSpec& spec, double runs, bool allowed, bool onRig = false) {
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

/// Draws figures with `write` under a QApplication (offscreen without a display); returns the
/// seconds it took.
template <typename Write>
double drawFigures(int argc, char** argv, Write write) {
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

/// The arguments of run, seeds, compare and analyse: one experiment file (and for analyse a
/// recording, for compare a second experiment), --out, the whole-number options that command
/// takes (--seed, --from, --to, --jobs), the text options it takes (--rig, --show) and
/// --no-figures where allowed. An error is the message to print.
struct RunArguments {
    std::string experimentPath, recordingPath, outDir;
    std::map<std::string, std::uint64_t> seeds;  ///< the whole-number options as given
    std::map<std::string, std::string> texts;    ///< "--rig", "--show" as given
    bool figures = true;
    bool replace = false;        ///< --replace: an earlier run in --out may be removed
    bool allowLongPlan = false;  ///< --allow-long-plan: a plan beyond the bounds is meant
    std::string error;

    std::string text(const std::string& option) const {
        const auto it = texts.find(option);
        return it == texts.end() ? std::string() : it->second;
    }
};

/// `textOptions` maps each text option the command takes to what it needs, e.g. {"--rig", "a rig
/// file, e.g. rig.json"}.
RunArguments parseRunArguments(const std::vector<std::string>& args, const char* command,
                               const std::vector<std::string>& seedOptions, bool figuresOption,
                               bool takesRecording = false,
                               const std::map<std::string, std::string>& textOptions = {}) {
    RunArguments r;
    auto fail = [&](const std::string& message) {
        r.error = message;
        return r;
    };
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const bool seedOption =
            std::find(seedOptions.begin(), seedOptions.end(), a) != seedOptions.end();
        if (a == "--out") {
            if (i + 1 >= args.size()) return fail("--out needs a folder");
            r.outDir = args[++i];
        } else if (seedOption) {
            if (i + 1 >= args.size()) return fail(a + " needs a whole number");
            const std::string& v = args[++i];
            const auto n = parseSeed(v);
            if (!n) return fail(a + " '" + v + "' is not a whole number between 0 and 2147483647");
            r.seeds[a] = *n;
        } else if (const auto text = textOptions.find(a); text != textOptions.end()) {
            if (i + 1 >= args.size()) return fail(a + " needs " + text->second);
            r.texts[a] = args[++i];
        } else if (a == "--no-figures" && figuresOption) {
            r.figures = false;
        } else if (a == "--replace") {
            r.replace = true;
        } else if (a == "--allow-long-plan" && std::string(command) != "analyse" &&
                   std::string(command) != "replay") {
            r.allowLongPlan = true;
        } else if (!a.empty() && a[0] == '-') {
            return fail("unknown option '" + a + "'");
        } else if (r.experimentPath.empty()) {
            r.experimentPath = a;
        } else if (takesRecording && r.recordingPath.empty()) {
            r.recordingPath = a;
        } else {
            return fail("unexpected argument '" + a + "'");
        }
    }
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

/// The seeds --from and --to give and how many run at once (--jobs, else one per core), or why
/// they give none.
struct SeedRange {
    std::uint64_t first = 0, last = 0;
    int jobs = 1;
    std::string error;
};

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
    return r;
}

struct Timing {
    double wall_s = 0.0, figures_s = 0.0;
};

/// Writes a finished run's tables, its figures if asked, and last its summary.json.
Timing writeArtefacts(const RunResult& result, const std::string& outDir, bool figures, int argc,
                      char** argv, std::chrono::steady_clock::time_point start) {
    writeRunTables(result, outDir);
    Timing t;
    if (figures)
        t.figures_s = drawFigures(argc, argv,
                                  [&] { writeRunFigures(result, QString::fromStdString(outDir)); });
    t.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeSummary(result, outDir, t.wall_s, t.figures_s);
    return t;
}

/// How a trial ended and what it measured, as a run's report gives it after "trial N: ".
void printTrialMeasures(const TrialRun& t) {
    std::printf(
        "%-38s %4zu taps, %6.0f s robot time, coverage %3.0f %%, contour distance mean %.2f max "
        "%.2f mm%s%s%s\n",
        trialEndName(t.result.end), t.result.taps.size(), t.result.robotTime_s,
        100.0 * t.result.coverage, t.result.meanContourDistance_mm, t.result.maxContourDistance_mm,
        t.recognised ? ", recognised as " : "", t.recognised ? t.recognition.predicted.c_str() : "",
        t.result.completed() ? "" : (", furthest " + describePlace(t.result.furthest)).c_str());
}

/// What a run or an analysis found: validation, noise floor, trials, recognition, where it went.
void printReport(const RunResult& result, double wall, double figures_s,
                 const std::string& outDir) {
    const ExperimentSpec& spec = result.spec;
    const auto& v = result.validation;
    std::printf(
        "validation: angle error %.2f deg, position error %.3f mm, class accuracy %.1f %%, "
        "%s\n",
        v.angleError_deg, v.positionError_mm, 100.0 * v.correctFraction,
        v.validRange.text().c_str());
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
    int labelWidth = 9;  // the columns line up whatever the trials are called
    for (const auto& t : result.trials) labelWidth = std::max(labelWidth, int(t.label.size()));
    for (const auto& t : result.trials) {
        std::printf("%-7s %-*s trial %d: ", modeName(t.result.mode), labelWidth, t.label.c_str(),
                    t.trial);
        printTrialMeasures(t);
    }
    if (!result.templates.empty())
        std::printf("recognition: %.0f %% of %s paths (smoothed histograms: %.0f %%)\n",
                    100.0 * result.recognitionAccuracy, modeName(spec.recognition.ofMode),
                    100.0 * result.recognitionAccuracySmoothed);
    std::printf("wall time %.3f s (figures %.3f s); results in %s\n", wall, figures_s,
                outDir.c_str());
}

int commandRun(const std::vector<std::string>& args, int argc, char** argv) {
    const RunArguments parsed = parseRunArguments(args, "run", {"--seed"}, true, false,
                                                  {{"--rig", "a rig file, e.g. rig.json"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    const std::string& experimentPath = parsed.experimentPath;
    std::string outDir = parsed.outDir;
    std::optional<std::uint64_t> seed;
    if (parsed.seeds.count("--seed")) seed = parsed.seeds.at("--seed");
    const bool figures = parsed.figures;

    const auto start = std::chrono::steady_clock::now();
    const auto loaded = loadForRun(experimentPath);
    if (!loaded) return kBadInput;
    const ExperimentSpec& spec = *loaded;
    // Devices named by a rig file: everything about them is checked before anything connects.
    std::optional<RigConfig> rigConfig;
    if (const std::string rigPath = parsed.text("--rig"); !rigPath.empty()) {
        try {
            rigConfig = readRigFile(rigPath, spec.scene);
            checkRunnableOn(spec, spec.scene.object);
        } catch (const InputError& e) {
            std::fprintf(stderr, "error: %s\n", e.what());
            return kBadInput;
        }
    }
    if (!planAccepted(spec, 1, parsed.allowLongPlan, rigConfig.has_value())) return kBadInput;
    if (outDir.empty()) outDir = (fs::path("results") / spec.name).string();
    const auto claimed = claimOrSay(outDir, "run", spec, runFactsOf(spec), parsed.replace);
    if (!claimed) return kBadInput;

    RunResult result;
    try {
        RunOptions options;
        options.simulated = &simulatedRigs();
        options.outDir = outDir;
        options.seed = seed;
        if (rigConfig) {
            // The serial port and the YARP socket run on Qt's event machinery.
            int qtArgc = 1;
            QCoreApplication app(qtArgc, argv);
            auto model = std::make_shared<const FingertipContactModel>(spec.scene.fingertip);
            std::printf("connecting %s\n", rigConfig->describe().c_str());
            std::fflush(stdout);
            // From here Ctrl-C stops what the devices do (the origin search, then the run after
            // the tap in flight) instead of ending the process.
            const InterruptHandlers handlers;
            rigConfig->yamaha.stopOriginSearch = &gInterrupted;
            std::unique_ptr<AssembledRig> assembled;
            try {
                assembled = std::make_unique<AssembledRig>(spec.scene, model, *rigConfig);
            } catch (const RigError& e) {
                std::fprintf(stderr, "%s: %s\nNothing was recorded.\n",
                             gInterrupted ? "stopped while connecting" : "could not connect",
                             e.what());
                return kRunFailed;
            }
            if (gInterrupted) {  // the rig lets the devices go as it ends
                std::fprintf(stderr, "stopped while connecting; nothing was recorded.\n");
                return kRunFailed;
            }
            const ConnectedRig connected{assembled->rig(), spec.scene.object,
                                         rigConfig->describe()};
            options.connected = &connected;
            options.cancel = &gInterrupted;
            result = runExperiment(spec, options);
            assembled->shutdown();
        } else {
            // Ctrl-C stops after the tap in flight, as on a rig, keeping every tap taken.
            const InterruptHandlers handlers;
            options.cancel = &gInterrupted;
            result = runExperiment(spec, options);
        }
        const Timing t = writeArtefacts(result, outDir, figures, argc, argv, start);
        if (rigConfig) {
            std::size_t taps = result.taps.size();
            for (const auto& trial : result.trials) taps += trial.result.taps.size();
            std::printf("%s: %zu taps on %s, %.0f s of robot time\n", spec.name.c_str(), taps,
                        result.rig.c_str(), result.robotTime_s);
        } else {
            std::printf("%s (seed %llu): %zu taps simulated, %.0f s of robot time\n",
                        spec.name.c_str(), static_cast<unsigned long long>(result.spec.scene.seed),
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
        // Read whole before anything is written: the output may be where the recording lies.
        RecordedRun recorded;
        if (replay)
            recorded = readRecordedRun(parsed.recordingPath, spec.classes);
        else
            recorded.taps =
                readTapCsv(parsed.recordingPath, spec.classes, &recorded.tapsCutOff,
                           checkedRecordingBounds(parsed.recordingPath, &recorded.note));
        const std::vector<CollectedTap>& taps = recorded.taps;
        const std::string& cut = recorded.tapsCutOff;
        RunOptions options;
        options.simulated = &simulatedRigs();
        options.outDir = outDir;
        options.recordedTaps = &taps;
        options.recordedTrials = replay ? &recorded.trials : nullptr;
        options.recordingName = parsed.recordingPath;
        if (!recorded.note.empty()) std::fprintf(stderr, "caution: %s\n", recorded.note.c_str());
        // The folder is claimed once the recording has passed every check: a refused one
        // writes nothing.
        std::optional<RunFolderClaim> claimed;
        options.beforeWriting = [&] {
            claimed.emplace(outDir, command, spec.name, runFactsOf(spec, &taps), parsed.replace);
        };
        const RunResult result = runExperiment(spec, options);
        const Timing t = writeArtefacts(result, outDir, parsed.figures, argc, argv, start);
        if (replay)
            std::printf(
                "%s: %zu recorded training and test taps and %d following taps over %d trials "
                "from %s replayed (%.0f s of recorded robot time)\n",
                spec.name.c_str(), result.taps.size(), recorded.followingTaps,
                static_cast<int>(recorded.trials.size()), parsed.recordingPath.c_str(),
                result.robotTime_s);
        else
            std::printf(
                "%s: %zu recorded taps from %s re-analysed (recorded over %.0f s of robot "
                "time)\n",
                spec.name.c_str(), result.taps.size(), parsed.recordingPath.c_str(),
                result.robotTime_s);
        if (!cut.empty())
            std::printf(
                "the recording was cut short at the end, as by a run stopped while "
                "writing: %s; that tap is left out\n",
                cut.c_str());
        if (!recorded.trialsCutOff.empty())
            std::printf(
                "the following recording was cut short at the end: %s; that tap is left out\n",
                recorded.trialsCutOff.c_str());
        for (const TrialRun& t : result.trials) {
            if (t.recordedTaps < 0) continue;
            if (t.result.end == TrialEnd::LeftRecording)
                std::printf("replayed %s %s trial %d: %s\n", modeName(t.result.mode),
                            t.label.c_str(), t.trial, t.result.detail.c_str());
            else
                std::printf("replayed %s %s trial %d: %zu of %d recorded taps retraced, %s\n",
                            modeName(t.result.mode), t.label.c_str(), t.trial, t.result.taps.size(),
                            t.recordedTaps, trialEndName(t.result.end));
        }
        const SweepSpec& sweeps = spec.sweeps;
        if (!result.sweeps.compute.empty())
            std::printf(
                "sweep (c): %zu settings of bins and samples per tap measured on the "
                "recorded taps\n",
                result.sweeps.compute.size());
        if (!sweeps.beliefThresholds.empty() || !sweeps.followSteps_mm.empty())
            std::printf(
                "sweeps (a) and (b) take new taps and follow contours on simulated rigs: "
                "not run on a recording\n");
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

/// The closing line of a run over seeds: wall time since `start`, of which figures, and where.
/// The end every command over seeds shares: `run` does the runs and prints as it goes, giving
/// what it found; `figures` (unless `drawn` is false) draws that; then the wall time. Bad input
/// exits 2; any other failure exits 1, saying that the seeds finished so far are in
/// `outDir`/`table` (`what` names the command's failure: "run failed", "compare failed").
template <typename Run, typename Figures>
int overSeeds(const char* what, const std::string& outDir, const char* table, bool drawn, int jobs,
              int argc, char** argv, Run run, Figures figures) {
    try {
        const auto start = std::chrono::steady_clock::now();
        const auto found = run();
        double figures_s = 0.0;
        if (drawn) figures_s = drawFigures(argc, argv, [&] { figures(found); });
        std::printf("wall time %.1f s (figures %.1f s; seeds run %d at a time); results in %s\n",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                    figures_s, jobs, outDir.c_str());
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\nThe seeds finished so far are in %s/%s.\n", what, e.what(),
                     outDir.c_str(), table);
        return kRunFailed;
    }
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
        std::printf("    run failed, %d trials not run: %s\n", o.trialsNotRun, o.runFailure.c_str());
    for (const auto& f : o.passiveShortfalls) std::printf("    %s\n", f.c_str());
    for (const auto& f : o.failures) std::printf("    %s\n", f.c_str());
    for (const auto& m : o.misnamed()) std::printf("    %s\n", m.c_str());
    std::fflush(stdout);
    return true;
}

/// The closing report of a seeds run or a merge: the rates over `first`..`last`.
void printSeedRates(const std::string& name, const SeedRates& rates, std::uint64_t first,
                    std::uint64_t last) {
    std::printf("\n%s over %zu seeds (%llu-%llu):\n", name.c_str(), rates.seeds.size(),
                static_cast<unsigned long long>(first), static_cast<unsigned long long>(last));
    for (const std::string& line : describeRates(rates)) std::printf("%s\n", line.c_str());
}

int commandSeeds(const std::vector<std::string>& args, int argc, char** argv) {
    const RunArguments parsed =
        parseRunArguments(args, "seeds", {"--from", "--to", "--jobs"}, true, false,
                          {{"--shard", "K/N, e.g. 2/3 for the second of three shards"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    const std::string& experimentPath = parsed.experimentPath;
    std::string outDir = parsed.outDir;
    const SeedRange range = seedRangeOf(parsed, "seeds --from 1 --to 10");
    if (!range.error.empty()) return usageError(range.error);
    Shard shard;
    if (const std::string text = parsed.text("--shard"); !text.empty()) {
        std::string error;
        const auto read = parseShard(text, &error);
        if (!read) return usageError(error);
        shard = *read;
    }
    // This shard's block of the range; a shard of more shards than seeds may have none.
    const auto seeds = shardSeeds(range.first, range.last, shard);
    const auto loaded = loadForRun(experimentPath);
    if (!loaded) return kBadInput;
    const ExperimentSpec& spec = *loaded;
    const double runs = seeds ? double(seeds->second - seeds->first + 1) : 0.0;
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
                                        range.first, range.last, shard, rates.seeds});
            if (shard.count > 1)
                std::printf("\nshard %d/%d of seeds %llu-%llu: %s\n", shard.index, shard.count,
                            static_cast<unsigned long long>(range.first),
                            static_cast<unsigned long long>(range.last),
                            seeds ? (std::to_string(seeds->first) + "-" +
                                     std::to_string(seeds->second))
                                        .c_str()
                                  : "no seeds");
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

int commandMerge(const std::vector<std::string>& args, int argc, char** argv) {
    std::vector<std::string> folders;
    std::string outDir;
    bool figures = true, replace = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--out") {
            if (i + 1 >= args.size()) return usageError("--out needs a folder");
            outDir = args[++i];
        } else if (args[i] == "--no-figures") {
            figures = false;
        } else if (args[i] == "--replace") {
            replace = true;
        } else if (!args[i].empty() && args[i][0] == '-') {
            return usageError("unknown option '" + args[i] + "'");
        } else {
            folders.push_back(args[i]);
        }
    }
    if (folders.empty())
        return usageError("merge needs the folders of the shards, e.g. merge S1 S2 S3 --out M");
    if (outDir.empty()) return usageError("merge needs --out, the folder to write");
    SeedShardFile merged;
    try {
        merged = mergeSeedShards(folders);
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
        const TrialPairRun pair = runTrialPair(simulatedRigs(), a, b, ref.seed, ref.mode, ref.label, ref.trial);
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

int commandCompare(const std::vector<std::string>& args, int argc, char** argv) {
    const RunArguments parsed =
        parseRunArguments(args, "compare", {"--from", "--to", "--jobs"}, true, true,
                          {{"--show", "a trial: seed,mode,label,trial, e.g. 3,active,cross,2"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    const std::string show = parsed.text("--show");
    std::optional<TrialRef> ref;
    SeedRange range;
    if (!show.empty()) {
        if (parsed.seeds.count("--from") || parsed.seeds.count("--to") ||
            parsed.seeds.count("--jobs"))
            return usageError(
                "--show runs the one seed it names; leave out --from, --to and --jobs");
        auto read = parseTrialRef(show);
        if (auto* error = std::get_if<std::string>(&read)) return usageError(*error);
        ref = std::get<TrialRef>(read);
    } else {
        range = seedRangeOf(parsed, "compare --from 1 --to 100");
        if (!range.error.empty()) return usageError(range.error);
    }
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
    const double seeds = double(range.last - range.first + 1);
    if (!planAccepted(*a, seeds, parsed.allowLongPlan) ||
        !planAccepted(*b, seeds, parsed.allowLongPlan))
        return kBadInput;
    const auto claimed = claimOrSay(outDir, "compare", *a, runFactsOf(*a), parsed.replace);
    if (!claimed) return kBadInput;
    int failedRuns = 0;
    const int code = overSeeds(
        "compare failed", outDir, "compare.csv", parsed.figures, range.jobs, argc, argv,
        [&] {
            const PairedComparison c = comparePaired(simulatedRigs(),
                *a, *b, range.first, range.last, outDir,
                [](std::uint64_t seed, const std::vector<PairedTrial>& pairs,
                   const PairedComparison&) {
                    int differ = 0;
                    for (const PairedTrial& p : pairs) differ += p.differs();
                    std::printf("seed %llu: %zu trials paired, %d ended differently\n",
                                static_cast<unsigned long long>(seed), pairs.size(), differ);
                    for (const PairedTrial& p : pairs)
                        if (p.differs())
                            std::printf("    %s %s trial %d: a %s, b %s\n", modeName(p.mode),
                                        p.label.c_str(), p.trial,
                                        endedText(p.outcomeA, p.namedA).c_str(),
                                        endedText(p.outcomeB, p.namedB).c_str());
                    std::fflush(stdout);
                    return true;
                },
                range.jobs);
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

int commandCheck(const std::vector<std::string>& argsIn) {
    std::vector<std::string> args;
    bool allowLongPlan = false;
    for (const std::string& a : argsIn) {
        if (a == "--allow-long-plan")
            allowLongPlan = true;
        else if (!a.empty() && a[0] == '-')
            return usageError("unknown option '" + a + "'");
        else
            args.push_back(a);
    }
    if (args.size() != 1) return usageError("check takes exactly one file");
    const std::string& file = args[0];
    if (file.size() > 4 && file.substr(file.size() - 4) == ".csv") {
        // A tap recording (data/taps.csv) or a following recording (data/following_taps.csv),
        // told apart by their header: every row, column and value checked, against the run's
        // run.json where it has one.
        try {
            std::string note;
            const RecordingBounds bounds = checkedRecordingBounds(file, &note);
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
            const auto taps = readTapCsv(file, ClassSet{}, &cut, bounds);
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

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        printHelp();
        return kBadInput;
    }
    const std::string command = args.front();
    args.erase(args.begin());
    if (command == "--help" || command == "-h" || command == "help") {
        printHelp();
        return kOk;
    }
    if (command == "run") return commandRun(args, argc, argv);
    if (command == "seeds") return commandSeeds(args, argc, argv);
    if (command == "analyse" || command == "analyze")
        return commandAnalyse(args, argc, argv, false);
    if (command == "replay") return commandAnalyse(args, argc, argv, true);
    if (command == "compare") return commandCompare(args, argc, argv);
    if (command == "check") return commandCheck(args);
    if (command == "merge") return commandMerge(args, argc, argv);
    return usageError("unknown command '" + command +
                      "'; use run, seeds, merge, compare, analyse, replay or check");
}
