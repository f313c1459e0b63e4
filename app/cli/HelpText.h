#pragma once
// What activetouch-cli prints for --help.
#include <string>

namespace activetouch::cli {

/// Every command's usage, the rules every command keeps and the exit codes, to stdout.
void printHelp();
/// `command`'s usage (analyse's for "analyze" too) to stdout; false for no such command.
bool printCommandHelp(const std::string& command);

}  // namespace activetouch::cli
