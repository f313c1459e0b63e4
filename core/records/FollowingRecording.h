#pragma once
// The recording of contour-following trials: every tap with its pose, time, samples, percept and
// decision, appended and flushed as it is taken, so a run that dies loses at most the tap in
// flight. Long format: one row per (tap, sample), one column per taxel.
#include <string>
#include <vector>

#include "core/control/ContourFollower.h"
#include "core/io/Csv.h"
#include "core/io/OutputFile.h"

namespace activetouch {

class FollowingRecording {
public:
    /// Opens (truncating) `path`; throws InputError if it cannot be written, and from
    /// `append` a WriteError if a write fails.
    FollowingRecording(const std::string& path, int taxels);
    FollowingRecording(const FollowingRecording&) = delete;
    FollowingRecording& operator=(const FollowingRecording&) = delete;

    void append(const std::string& label, FollowingMode mode, int trial, int tapIndex,
                const FollowedTap& tap);

private:
    OutputFile file_;
    int taxels_;
};

/// What a recording holds, as checkFollowingRecording found it.
struct FollowingRecordingContents {
    int taps = 0;           ///< whole taps
    int trials = 0;         ///< (shape, mode, trial) runs with at least one whole tap
    int samplesPerTap = 0;  ///< of every whole tap
    /// Empty, or what the end of the file lost: a run stopped while writing a tap leaves the
    /// finished taps whole and that one tap cut short.
    std::string cutOff;
};

/// Reads a recording written by FollowingRecording and checks every row: the columns, numbers
/// (finite; pressures within 0..255 counts), mode, ending, rule, and that each trial's taps run
/// 0, 1, 2, ... with their samples 0, 1, 2, ... and as many samples as every other tap. Only the
/// end of the file may be cut short (reported, not an error). Throws InputError naming the file,
/// the line, the column and the problem.
/// Every row is held to `bounds` and to its tap's first row (the tap's own columns are the same
/// on all its rows), posteriors lie in 0..1 and robot times never run backwards within a trial.
FollowingRecordingContents checkFollowingRecording(const std::string& path,
                                                   const RecordingBounds& bounds = {});

/// What the recorded run perceived and decided at a tap, as the recording words it.
struct RecordedDecision {
    std::string shapeClass;  ///< "lower edge", "plane", ...
    int position = 0;
    std::string rule;  ///< the rules table's name
};

/// One trial as a recording holds it: its whole taps in order, each with its pose, robot time,
/// how the stroke ended and its samples (what a rig gave), and beside them what the recorded run
/// perceived and decided.
struct RecordedTrial {
    std::string label;
    FollowingMode mode = FollowingMode::Active;
    int trial = 1;
    std::vector<TapRecord> taps;
    std::vector<RecordedDecision> decisions;  ///< one per tap
};

/// Reads and checks a recording as checkFollowingRecording does, keeping every whole tap.
std::vector<RecordedTrial> readFollowingRecording(const std::string& path,
                                                  FollowingRecordingContents* contents = nullptr,
                                                  const RecordingBounds& bounds = {});

}  // namespace activetouch
