#pragma once
// What the project's CSV readers and tap writers share: splitting a line (the project writes no
// quoted fields), reading a finite number from a field, with an error that names the file, line
// and column, and the header of a table with a row per (tap, sample).
#include <cstddef>
#include <fstream>
#include <istream>
#include <string>
#include <vector>

#include "core/common/Limits.h"
#include "core/geometry/Vec2.h"
#include "core/io/InputFile.h"

namespace activetouch {

class OutputFile;

/// What every row of a recording is held to besides itself (docs/limits.md).
struct RecordingBounds {
    /// Samples every tap has; 0: as many as the file's first tap. A run's run.json gives it.
    int samplesPerTap = 0;
    /// Poses lie within 0..travel on each axis.
    Vec2 travel_mm{kMaxStageTravel_mm, kMaxStageTravel_mm};
    /// Taxel columns every row has; 0: as many as the header names. A run's run.json, or the
    /// experiment the recording is checked with, gives it.
    int taxels = 0;
    /// Where `taxels` comes from, for the message that refuses another count.
    std::string taxelsFrom;
};

/// Refuses (naming line 1) a recording with `taxels` columns where `bounds` asks for others.
void checkTaxelCount(int taxels, const RecordingBounds& bounds, const std::string& path);

/// A recording larger than this is refused before it is read (docs/limits.md).
inline constexpr unsigned long long kMaxRecordingBytes = 1ull << 30;
/// A recording's line longer than this is refused: a row of a 12-taxel tap is under 600 bytes.
inline constexpr std::size_t kMaxRecordingLineBytes = 1u << 16;

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

/// Refuses a tap pose outside 0..bounds.travel_mm (`x`, `y`: the values as written), naming the
/// line and the column.
void checkPose(Vec2 pose, const RecordingBounds& bounds, const std::string& path, int line,
               const std::string& x, const std::string& y,
               const std::string& xColumn = "pose_x_mm", const std::string& yColumn = "pose_y_mm");

/// Refuses a robot time below 0 or below `previous` (the tap before it), naming the line and
/// the column; `field` is the value as written.
void checkTime(double time, double previous, const std::string& path, int line,
               const std::string& field, const std::string& column = "robot_time_s");

/// Refuses a row whose first `count` fields (the tap's own columns, named by `columns`) differ
/// from those of the tap's first row `first`, at `firstLine`.
void sameAsFirstRow(const std::vector<std::string>& row, const std::vector<std::string>& first,
                    const char* const* columns, int count, const std::string& path, int line,
                    int firstLine);

/// `path` opened for reading as a recording; InputError if it is missing, unreadable or over
/// kMaxRecordingBytes.
std::ifstream openRecording(const std::string& path);

/// The rows of a recording written and flushed row by row: every row as wide as the header, but
/// the file's last line, which a run stopped while writing may have cut short.
class RecordingRows {
public:
    /// Reads the header line; throws InputError if the file is empty. Every line is refused past
    /// kMaxRecordingLineBytes.
    RecordingRows(std::istream& in, const std::string& path);
    const std::vector<std::string>& header() const { return header_; }
    /// The next row as wide as the header, or false at the end of the file. Empty lines are
    /// skipped; a line of another width is held back and refused if any row follows it.
    bool next(std::vector<std::string>& fields);
    int line() const { return line_; }  ///< the line of the row `next` gave
    /// Empty, or "line N is cut off (has F fields, the header has W)".
    std::string cutOff() const;

private:
    BoundedLines lines_;
    std::string path_;
    std::vector<std::string> header_;
    int line_ = 1, brokenAt_ = 0;
    std::string broken_;
};

}  // namespace activetouch
