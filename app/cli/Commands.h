#pragma once
// The commands of activetouch-cli, one file each (docs/command-line.md). Each takes the arguments
// after its name and returns the exit code: 0 ok, 1 the run failed, 2 bad input.
#include <string>
#include <vector>

namespace activetouch::cli {

int commandRun(const std::vector<std::string>& args, int argc, char** argv);
/// analyse, or with `replay` replay.
int commandAnalyse(const std::vector<std::string>& args, int argc, char** argv, bool replay);
int commandSeeds(const std::vector<std::string>& args, int argc, char** argv);
int commandMerge(const std::vector<std::string>& args, int argc, char** argv);
int commandCompare(const std::vector<std::string>& args, int argc, char** argv);
int commandCheck(const std::vector<std::string>& args);
int commandImport(const std::vector<std::string>& args);
int commandImportFrames(const std::vector<std::string>& args);
int commandFingertipStats(const std::vector<std::string>& args, int argc, char** argv);
int commandDump(const std::vector<std::string>& args);
int commandCalibrate(const std::vector<std::string>& args, int argc, char** argv);

}  // namespace activetouch::cli
