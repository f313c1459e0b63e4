#pragma once
// What the project's CSV readers share: splitting a line (the project writes no quoted fields)
// and reading a finite number from a field, with an error that names the file, line and column.
#include <string>
#include <vector>

namespace activetouch {

/// The fields of one line, split at every comma; a trailing '\r' goes.
std::vector<std::string> splitCsvLine(const std::string& line);

/// The number in `field`; throws InputError(path, "line N, column C", ...) if it is not a number
/// or not finite.
double csvNumber(const std::string& field, const std::string& path, int line,
                 const std::string& column);

}  // namespace activetouch
