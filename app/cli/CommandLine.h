#pragma once
// The arguments of one command, read with QCommandLineParser: options that take a value (as
// "--out dir" or "--out=dir"), flags, and the positional arguments, with an error a user can act
// on when they do not fit.
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace activetouch::cli {

struct CommandSyntax {
    /// Options that take a value, with what the value is: {"--out", "a folder"}.
    std::vector<std::pair<std::string, std::string>> values;
    std::vector<std::string> flags;  ///< options without a value: "--no-figures"
};

struct CommandLine {
    std::vector<std::string> positional;
    std::map<std::string, std::string> values;  ///< the value options given (the last of each)
    std::vector<std::string> flags;             ///< the flags given
    /// Empty, or what does not fit: "unknown option '--x'", "--out needs a folder".
    std::string error;

    bool has(const std::string& flag) const;
    /// The value given to `option`, or empty.
    std::string value(const std::string& option) const;
};

CommandLine parseCommandLine(const CommandSyntax& syntax, const std::vector<std::string>& args);

}  // namespace activetouch::cli
