// activetouch-cli: the headless runner (docs/design.md §5).
//   activetouch-cli run <experiment.json> [--out <dir>] [--seed N] [--rig <rig>] [--no-figures]
//   activetouch-cli seeds <experiment.json> --from A --to B [--out <dir>] [--no-figures]
//   activetouch-cli analyse <experiment.json> <taps.csv> [--out <dir>] [--no-figures]
//   activetouch-cli replay <experiment.json> <run folder> [--out <dir>] [--no-figures]
//   activetouch-cli import <experiment.json> <dumper log> --taxel-map <map> [--poses <log>]
//   activetouch-cli check <file.json | taps.csv | following_taps.csv>
// Exit codes: 0 ok, 1 the run failed, 2 bad input.
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/CliSupport.h"
#include "app/cli/Commands.h"
#include "app/cli/HelpText.h"
#include "app/figures/Installation.h"
#include "core/common/HeapTuning.h"

using namespace activetouch;
using namespace activetouch::cli;

int main(int argc, char** argv) {
    useInstalledResources();  // an installed binary reads the resources installed beside it
    keepHeapBetweenRuns();
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        printHelp();
        return kBadInput;
    }
    std::string command = args.front();
    args.erase(args.begin());
    if (command == "analyze") command = "analyse";
    // `activetouch-cli <command> --help`: that command's usage, whatever else is given.
    for (const std::string& a : args)
        if ((a == "--help" || a == "-h") && printCommandHelp(command)) return kOk;
    if (command == "--help" || command == "-h" || command == "help") {
        printHelp();
        return kOk;
    }
    if (command == "--version") {
        std::printf("activetouch-cli %s\n", ACTIVETOUCH_VERSION);
        return kOk;
    }
    if (command == "run") return commandRun(args, argc, argv);
    if (command == "seeds") return commandSeeds(args, argc, argv);
    if (command == "analyse") return commandAnalyse(args, argc, argv, false);
    if (command == "replay") return commandAnalyse(args, argc, argv, true);
    if (command == "compare") return commandCompare(args, argc, argv);
    if (command == "check") return commandCheck(args);
    if (command == "merge") return commandMerge(args, argc, argv);
    if (command == "import") return commandImport(args);
    if (command == "import-frames") return commandImportFrames(args);
    if (command == "fingertip-stats") return commandFingertipStats(args, argc, argv);
    if (command == "dump") return commandDump(args);
    if (command == "calibrate") return commandCalibrate(args, argc, argv);
    return usageError("unknown command '" + command +
                      "'; use run, seeds, merge, compare, analyse, replay, import, dump,\n"
                      "calibrate, import-frames, fingertip-stats or check");
}
