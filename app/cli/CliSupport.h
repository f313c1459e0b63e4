#pragma once
// What the commands of activetouch-cli share: exit codes, Ctrl-C, loading and checking an
// experiment, the argument parser, writing a run's artefacts and the reports they print.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/common/InputError.h"
#include "core/experiment/Experiment.h"
#include "core/run/ExperimentRun.h"
#include "core/run/RunArtefacts.h"
#include "core/run/RunFolder.h"
#include "core/analysis/SeedRates.h"
#include "core/analysis/SeedShards.h"

namespace activetouch::cli {

inline constexpr int kOk = 0, kRunFailed = 1, kBadInput = 2;

/// Set by Ctrl-C (SIGINT) or SIGTERM on devices: while connecting, the stage's origin search is
/// stopped; in the run, the run stops after the tap in flight, leaves the tapper retracted and
/// the stage still, and keeps every tap taken.
extern std::atomic<bool> gInterrupted;

extern "C" void onInterrupt(int);

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

int usageError(const std::string& message);

/// Says, before any tap, what an experiment will run but cannot do well.
void printCautions(const ExperimentSpec& spec);

/// The experiment a run or seeds command takes, checked, its cautions printed; on bad input the
/// message is printed and nothing is returned.
std::optional<ExperimentSpec> loadForRun(const std::string& path);

/// Refuses (printing why) a plan of `runs` runs of `spec` beyond the bounds, unless allowed;
/// `onRig`: its taps are taken on a rig, so its robot time is bounded too.
bool planAccepted(const ExperimentSpec& spec, double runs, bool allowed, bool onRig = false);

/// Claims `outDir` for a run (printing why not); while it lives, the folder's run.json is
/// completed with the run's files whenever the command ends.
std::optional<RunFolderClaim> claimOrSay(const std::string& outDir, const char* command,
                                         const ExperimentSpec& spec, const RunFacts& facts,
                                         bool replace);

void setUpHeadlessDisplay();

/// Draws figures with `write` under a QApplication (offscreen without a display); returns the
/// seconds it took.
double drawFigures(int argc, char** argv, const std::function<void()>& write);

std::optional<std::uint64_t> parseSeed(const std::string& v);

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
                               const std::map<std::string, std::string>& textOptions = {});

/// The seeds --from and --to give and how many run at once (--jobs, else one per core), or why
/// they give none.
struct SeedRange {
    std::uint64_t first = 0, last = 0;
    int jobs = 1;
    Shard shard;  ///< --shard K/N, else 1/1
    /// The shard's block of first..last; nothing for a shard of more shards than seeds.
    std::optional<std::pair<std::uint64_t, std::uint64_t>> seeds;
    std::string error;
    /// How many runs the block holds.
    double runs() const { return seeds ? double(seeds->second - seeds->first + 1) : 0.0; }
};

/// `example` is the command with a range, e.g. "seeds --from 1 --to 10". Reads --shard too, if
/// the command takes it.
SeedRange seedRangeOf(const RunArguments& parsed, const std::string& example);

/// For a shard of more than one, the line saying which block of the range it ran.
void printShardBlock(const SeedRange& range);

/// Writes a finished run's tables, its figures if asked (at `figureWidthMm` wide if > 0), and
/// last its summary.json.
ArtefactTiming writeArtefacts(const RunResult& result, const std::string& outDir, bool figures,
                              int argc, char** argv, std::chrono::steady_clock::time_point start,
                              double figureWidthMm = 0.0);

/// The width --figure-width-mm asks for (0 if not given), or why it cannot be used: a width from
/// kLeastFigureWidth_mm to kMostFigureWidth_mm.
inline constexpr double kLeastFigureWidth_mm = 60.0, kMostFigureWidth_mm = 300.0;
std::optional<double> figureWidthOf(const RunArguments& parsed, std::string& error);

/// How a trial ended and what it measured, as a run's report gives it after "trial N: ".
void printTrialMeasures(const TrialRun& t);

/// What a run or an analysis found: validation, noise floor, trials, recognition, where it went.
void printReport(const RunResult& result, double wall, double figures_s,
                 const std::string& outDir);

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
int failedRunsExit(int code, int failedRuns, const std::string& outDir, const char* where);

/// What a seeds run or a merge prints as each seed finishes.
bool printSeedOutcome(const SeedOutcome& o);

/// The closing report of a seeds run or a merge: the rates over `first`..`last`.
void printSeedRates(const std::string& name, const SeedRates& rates, std::uint64_t first,
                    std::uint64_t last);

}  // namespace activetouch::cli
