#pragma once
// Taps as CSV in long format: one row per (tap, sample) with one column per taxel, so pandas,
// MATLAB or R read it directly. The writer appends and flushes tap by tap, so a run that dies
// loses at most the tap in flight.
//
// Columns: set,class,orientation_deg,position,true_offset_mm,pose_x_mm,pose_y_mm,robot_time_s,
//          ending,sample,taxel_0..taxel_{K-1}
#include <string>
#include <vector>

#include "core/io/Csv.h"
#include "core/io/OutputFile.h"
#include "core/tap/ClassSet.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {

class TapCsvWriter {
public:
    /// Opens (truncating) `path`; throws InputError if it cannot be written, and from
    /// `append` a WriteError if a write fails.
    TapCsvWriter(const std::string& path, int taxels);
    TapCsvWriter(const TapCsvWriter&) = delete;
    TapCsvWriter& operator=(const TapCsvWriter&) = delete;

    void append(const CollectedTap& tap, const ClassSet& classes);

private:
    OutputFile file_;
    int taxels_;
};

/// Reads taps written by TapCsvWriter with `classes`. Throws InputError naming the file, the line
/// and the problem for wrong columns, non-numbers, NaN, values outside 0..255, a row whose
/// orientation and position are not its class's, or taps with unequal numbers of samples. A run
/// stopped while writing leaves its last tap (and maybe its last line) cut short: that tap is left
/// out and `cutOff` says what was cut; without `cutOff`, such a file is refused. Every row is held
/// to `bounds` and to its tap's first row: set, class, pose, time and ending are the tap's, poses
/// lie inside the travel, times are non-negative and never run backwards.
std::vector<CollectedTap> readTapCsv(const std::string& path, const ClassSet& classes,
                                     std::string* cutOff = nullptr,
                                     const RecordingBounds& bounds = {});

}  // namespace activetouch
