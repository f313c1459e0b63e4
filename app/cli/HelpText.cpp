// The help activetouch-cli prints: the whole of it for --help, one command's part for
// `activetouch-cli <command> --help`.
#include "app/cli/HelpText.h"

#include <cstdio>

namespace activetouch::cli {
namespace {

struct CommandHelp {
    const char* command;
    const char* text;
};

const CommandHelp kHelp[] = {
    {"run",
        "  activetouch-cli run <experiment.json> [--out <dir>] [--seed N] [--rig <rig.json>]\n"
        "                      [--no-figures] [--figure-width-mm W]\n"
        "      Runs the experiment on the simulated rig and writes <dir>/summary.json,\n"
        "      <dir>/data/*.csv (every tap, appended as it is taken; every table behind a figure)\n"
        "      and <dir>/figures/*.{png,pdf,svg}. --out defaults to results/<experiment name>.\n"
        "      --seed overrides the experiment's seed (one seed = one whole run).\n"
        "      --figure-width-mm writes every figure W mm wide (89: a journal's single column)\n"
        "      at its own height there, its panels wrapped to fit (docs/window.md).\n"
        "      --rig takes the taps on the devices a rig file names instead (the Yamaha stage,\n"
        "      the NXT tapper with the fingertip over YARP, or a mix with simulated ones; see\n"
        "      docs/real-rig.md): the scene's object must be the one mounted. Ctrl-C stops\n"
        "      after the tap in flight, keeping every tap taken (while connecting, it stops the stage's\n"
        "      origin search).\n"},
    {"seeds",
        "  activetouch-cli seeds <experiment.json> --from A --to B [--jobs N] [--out <dir>]\n"
        "                        [--no-figures]\n"
        "      Runs the experiment once per seed A..B (each a whole run: its own data sets,\n"
        "      training, valid range and trials) and reports the rates with 95 % intervals:\n"
        "      passive trials lost (and lost at a corner), active trials completed (and per\n"
        "      trial label, and per valid range the runs picked), where the trials that did\n"
        "      not complete got furthest, the convex and concave corners each mode got round,\n"
        "      active paths recognised by both rules (and which shapes each misnamed as\n"
        "      which), runs with the paper's result whole. Writes <dir>/rates.csv (a row per\n"
        "      seed, appended as each finishes), <dir>/rates.json (with the recognition\n"
        "      confusion) and <dir>/figures/seed_rates.{png,pdf,svg} (each seed's outcome and\n"
        "      the rates so far with their intervals). --out defaults to\n"
        "      results/<experiment name>_seeds. --jobs runs N seeds at once (default: one per\n"
        "      core); every row and rate is the same for any N, reported in seed order.\n"},
    {"seeds",
        "  activetouch-cli seeds <experiment.json> --from A --to B --shard K/N [...]\n"
        "      Runs only the K-th of N contiguous blocks of seeds A..B (for sweeps split across\n"
        "      machines); its folder keeps every seed's outcome in seed_outcomes.json.\n"},
    {"merge",
        "  activetouch-cli merge <folder>... --out <dir> [--no-figures]\n"
        "      Merges the folders of every shard of one seeds sweep (or one comparison) into\n"
        "      what one run over the whole range writes (rates.csv and rates.json, or\n"
        "      compare.csv, compare_so_far.csv and compare.json; figures); refuses shards that\n"
        "      overlap, leave seeds out, or ran other settings, naming the seeds and folders.\n"},
    {"compare",
        "  activetouch-cli compare <a.json> <b.json> --from A --to B [--jobs N] [--out <dir>]\n"
        "                          [--no-figures]\n"
        "      Runs both experiments once per seed A..B and compares them trial by trial: a\n"
        "      seed gives both the same data sets and the same noise on each trial, so where\n"
        "      they differ in a setting, the trials whose outcomes differ show its effect.\n"
        "      Prints each outcome's rate in a and in b, the trials only one completed (or\n"
        "      lost at a corner, or recognised), the difference with its 95 % interval and\n"
        "      McNemar's exact p, and the robot time per run. Writes <dir>/compare.csv (a row\n"
        "      per paired trial) and <dir>/compare_so_far.csv (each part's comparison after\n"
        "      each seed), both appended as each seed finishes, <dir>/compare.json and\n"
        "      <dir>/figures/compare.{png,pdf,svg} (each difference with its interval, and how\n"
        "      it settled seed by seed).\n"
        "      --out defaults to results/<a>_vs_<b>; --jobs as for seeds; --shard K/N runs\n"
        "      the K-th of N blocks of the seeds, as for seeds (compare_seeds.json keeps each\n"
        "      seed's record to merge).\n"},
    {"compare",
        "  activetouch-cli compare <a.json> <b.json> --show SEED,MODE,LABEL,TRIAL [--out <dir>]\n"
        "                          [--no-figures]\n"
        "      Runs that seed in both experiments and shows that trial (as the first four\n"
        "      columns of a compare.csv row name it, e.g. 3,active,cross,2) as each ran it:\n"
        "      prints how each ended and what it measured, and writes\n"
        "      <dir>/trial_pair_seed<S>_<mode>_<label>_<trial>.csv (both paths, tap by tap)\n"
        "      and the same name under <dir>/figures as .png, .pdf and .svg (the object, both\n"
        "      paths with their taps, where a lost trial ended and how far it got).\n"},
    {"analyse",
        "  activetouch-cli analyse <experiment.json> <taps.csv> [--out <dir>] [--no-figures]\n"
        "      Re-analyses recorded training and test taps (a run's data/taps.csv, from the\n"
        "      simulated or the real rig) with the experiment's classes, classifier, training\n"
        "      and validation settings: trains, validates and writes summary.json, the tables\n"
        "      and Figures 5 and 6. --out defaults to results/<experiment name>_analysis.\n"},
    {"replay",
        "  activetouch-cli replay <experiment.json> <run folder> [--out <dir>] [--no-figures]\n"
        "      Replays a run's recording (<run folder>/data/taps.csv and following_taps.csv,\n"
        "      from the simulated or the real rig) as a rig: trains and validates on the\n"
        "      recorded taps, then runs every trial of the experiment, served the recorded tap\n"
        "      wherever the recorded run tapped. With the run's own settings every trial\n"
        "      retraces its recording; with others, each trial says at which tap it decided\n"
        "      otherwise and left the recording. --out defaults to\n"
        "      results/<experiment name>_replay.\n"},
    {"import",
        "  activetouch-cli import <experiment.json> <dumper folder | data.log>\n"
        "                         --taxel-map <map> [--poses <pose log>] [--threshold N]\n"
        "                         [--lead-frames N] [--out <dir>]\n"
        "      Imports a skin log written by YARP's data dumper as the tap recording of the\n"
        "      experiment's training protocol (<dir>/data/taps.csv, ready for analyse): the\n"
        "      taxel map says which values are the fingertip's taxels; with the stage's pose\n"
        "      log each tap starts where the log says, without it taps are found where the\n"
        "      total pressure crosses the reflex threshold (the scene's, or --threshold).\n"
        "      A bad line in any file is refused, naming it. --out defaults to\n"
        "      results/<experiment name>_import.\n"},
    {"import-frames",
        "  activetouch-cli import-frames <layout.json> <recording>... --out <dir> [--replace]\n"
        "      Reads real skin recordings in a frames-table layout (one frame per line or per\n"
        "      group of lines; the layout names each finger's taxels, inverted 8-bit readings\n"
        "      and any time stamp; docs/real-fingertips.md) into <dir>/frames.csv and\n"
        "      frames.json. A line that does not fit the layout is refused, naming it.\n"},
    {"fingertip-stats",
        "  activetouch-cli fingertip-stats <import dir> [--out <dir>] [--finger F] [--scenes a,b]\n"
        "                                  [--write-scene F] [--rest-margin N] [--no-figures]\n"
        "      What the imported frames say of each finger's taxels where poses are unknown:\n"
        "      resting offset, noise, quantisation step, drift over a recording, dead and stuck\n"
        "      taxels, the range reached under contact, the fingers' common movement at rest,\n"
        "      with 95 % intervals over the recordings. Compares the finger's (--finger, index)\n"
        "      resting readings with each scene's simulated fingertip (--scenes, the paper's)\n"
        "      by the Kolmogorov-Smirnov distance; --write-scene writes the scene they call\n"
        "      for. --out writes fingertip_stats.json and figures/fingertip_stats.*.\n"},
    {"dump",
        "  activetouch-cli dump <experiment.json> <taps.csv> --taxel-map <map> --out <dir>\n"
        "      Writes a recording's taps as YARP's data dumper logs a skin port (<dir>/data.log,\n"
        "      info.log) with the stage's pose log (poses.log): for yarpdataplayer, or import.\n"},
    {"calibrate",
        "  activetouch-cli calibrate <experiment.json> <run folder | taps.csv>\n"
        "                            [--scene <base scene>] --out <fitted scene.json>\n"
        "                            [--replicates N] [--no-figures]\n"
        "      Fits a scene to recorded training and test taps (from the real rig or a\n"
        "      simulated one): noise, drift, quantisation, dead taxels and per-taxel gains,\n"
        "      each estimate with its uncertainty; lists only the effects the taps call for;\n"
        "      reports how well the fitted scene reproduces the taps (Kolmogorov-Smirnov per\n"
        "      taxel, Figure 6 recorded beside simulated). Beside the scene it writes\n"
        "      <stem>.calibration.json, <stem>.simulated_taps.csv and the figure\n"
        "      <stem>.calibration.{png,pdf,svg} (docs/calibration.md).\n"},
    {"check",
        "  activetouch-cli check <file.json | taps.csv | following_taps.csv>\n"
        "                        [--allow-long-plan]\n"
        "      Validates an experiment (and prints its plan: taps and robot time), a scene,\n"
        "      a rig file or a recording (training taps,\n"
        "      or following taps: a run stopped while writing leaves every finished tap whole\n"
        "      and the cut is reported) and says what is wrong, if anything.\n"},
};

const char* const kHead =
    "activetouch-cli - ActiveTouch Workbench headless runner\n"
    "\n";

const char* const kTail =
    "  activetouch-cli --help | --version\n"
    "\n"
    "Every command that writes a folder refuses one that already holds a run (its run.json,\n"
    "summary, tables or data) unless given --replace, which removes that run's files first;\n"
    "files of yours in the folder are left alone. run, seeds and compare refuse a plan\n"
    "beyond 10,000,000 taps, 24 h of robot time or 2 GiB of taps held in memory unless\n"
    "given --allow-long-plan; check prints the plan. Limits: docs/limits.md.\n"
    "\n"
    "Exit codes: 0 ok, 1 the run failed, 2 bad input (the message names the file, the place and the problem).\n";

}  // namespace

void printHelp() {
    std::fputs(kHead, stdout);
    std::fputs("Usage:\n", stdout);
    for (const CommandHelp& h : kHelp) std::fputs(h.text, stdout);
    std::fputs(kTail, stdout);
}

bool printCommandHelp(const std::string& command) {
    bool found = false;
    for (const CommandHelp& h : kHelp) {
        if (command != h.command) continue;
        if (!found) std::fputs("Usage:\n", stdout);
        std::fputs(h.text, stdout);
        found = true;
    }
    if (found)
        std::fputs("\nExit codes: 0 ok, 1 the run failed, 2 bad input (the message names the file, "
                   "the place and the problem). More: activetouch-cli --help, "
                   "docs/command-line.md.\n",
                   stdout);
    return found;
}

}  // namespace activetouch::cli
