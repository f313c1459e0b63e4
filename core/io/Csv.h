#pragma once
// What the project's CSV readers and tap writers share: splitting a line (the project writes no
// quoted fields), reading a finite number from a field, with an error that names the file, line
// and column, and the header of a table with a row per (tap, sample).
#include <istream>
#include <string>
#include <vector>

namespace activetouch {

class OutputFile;

/// Writes the header of a table with a row per (tap, sample): the `count` fixed `columns`, then
/// taxel_0 .. taxel_{taxels-1}; flushes it.
void writeTapTableHeader(OutputFile& file, const char* const* columns, int count, int taxels);

/// The fields of one line, split at every comma; a trailing '\r' goes.
std::vector<std::string> splitCsvLine(const std::string& line);

/// The number in `field`; throws InputError(path, "line N, column C", ...) if it is not a number
/// or not finite.
double csvNumber(const std::string& field, const std::string& path, int line,
                 const std::string& column);

/// The whole number in `field` (a set, class, trial, tap, sample or position), within
/// -1e9..1e9; throws InputError as csvNumber does, and also for a fraction.
int csvInteger(const std::string& field, const std::string& path, int line,
               const std::string& column);

/// The rows of a recording written and flushed row by row: every row as wide as the header, but
/// the file's last line, which a run stopped while writing may have cut short.
class RecordingRows {
public:
    /// Reads the header line; throws InputError if the file is empty.
    RecordingRows(std::istream& in, const std::string& path);
    const std::vector<std::string>& header() const { return header_; }
    /// The next row as wide as the header, or false at the end of the file. Empty lines are
    /// skipped; a line of another width is held back and refused if any row follows it.
    bool next(std::vector<std::string>& fields);
    int line() const { return line_; }  ///< the line of the row `next` gave
    /// Empty, or "line N is cut off (has F fields, the header has W)".
    std::string cutOff() const;

private:
    std::istream& in_;
    std::string path_;
    std::vector<std::string> header_;
    int line_ = 1, brokenAt_ = 0;
    std::string broken_;
};

}  // namespace activetouch
