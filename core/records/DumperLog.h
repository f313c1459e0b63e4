#pragma once
// Skin recordings made outside the workbench: the logs YARP's data dumper writes for a skin port
// (data.log: one line per frame, "counter stamp [stamp] value value ..."; info.log says whether a
// line carries one stamp or two), a taxel map saying which of a frame's values are the
// fingertip's taxels and in what order, and a stage's pose log (one line per tap: the robot time
// the tap began and where). Together with an experiment's training protocol they give the
// project's tap recording (docs/file-formats.md, "Skin logs from YARP's data dumper").
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/Polygon.h"
#include "core/io/Csv.h"
#include "core/tap/ClassSet.h"
#include "core/tap/Tap.h"
#include "core/validation/TrainingProtocol.h"

namespace activetouch {

/// Which value of a dumped frame each taxel of the fingertip is.
struct TaxelMap {
    int valuesPerFrame = 0;
    std::vector<int> valueOf;  ///< valueOf[k]: the 0-based index of taxel k's value in a frame
};

/// Reads a taxel map: lines "values_per_frame N", then either "finger index|middle|ring|little|
/// thumb" (that fingertip's 12 values in an iCub hand's 192) or one line "taxel K value V" per
/// taxel, K = 0, 1, ... in order; '#' starts a comment. Throws InputError naming the line for a
/// taxel out of order or listed twice (a shuffled map), a value used twice or past the frame, a
/// missing taxel or anything else it cannot read.
TaxelMap readTaxelMap(const std::string& path, int taxels);
/// The map as readTaxelMap reads it.
std::string taxelMapText(const TaxelMap& map);

/// A skin stream read from a dumper log, reduced to the fingertip's taxels.
struct SkinStream {
    std::string source;  ///< the data.log it was read from
    int taxels = 0;
    std::vector<std::uint64_t> counters;
    std::vector<double> times_s;
    std::vector<int> lines;      ///< the log line of each frame
    std::vector<double> values;  ///< frame-major: values[f * taxels + k]
    int stamps = 1;              ///< stamps per line (2: the dumper logged tx and rx; tx is used)
    std::int64_t framesMissing = 0;  ///< counter gaps over the whole log
    /// The least and largest of every value of the frame (mapped or not), over the log.
    std::vector<double> valueLow, valueHigh;

    std::size_t frameCount() const { return times_s.size(); }
    const double* frame(std::size_t f) const {
        return values.data() + f * static_cast<std::size_t>(taxels);
    }
};

/// Reads `path` (a dumper's folder holding data.log, or the data.log itself) through `map`.
/// Every line must hold a whole counter that never falls nor skips more frames than 1000 a second
/// of its stamps, one or two stamps (info.log's "Stamp:", else inferred from the first line) that
/// never run backwards, and exactly
/// map.valuesPerFrame finite values, each within 0..255; anything else is refused naming the
/// line and the field. An empty log is refused.
SkinStream readDumperLog(const std::string& path, const TaxelMap& map);

/// A taxel that is touched varies by at least this over a log of taps.
inline constexpr double kMinTouchRange_counts = 10.0;

/// Refuses (InputError naming `mapPath`) a map whose taxels never vary by kMinTouchRange_counts
/// over the log while another of the frame's values does: the map reads a fingertip that was
/// not touched (another finger's), and every tap would read nothing.
void checkMapReadsTheTouch(const SkinStream& stream, const TaxelMap& map,
                           const std::string& mapPath);

/// One line of a pose log: the robot time a tap began (the clock the dumper's stamps use) and the
/// commanded fingertip pose in stage millimetres.
struct PoseLogEntry {
    double time_s = 0.0;
    Vec2 pose;
    int line = 0;
};
/// Reads a pose log: lines "time_s x_mm y_mm" (or "counter time_s x_mm y_mm", as a dumper of a
/// stage port writes them); '#' starts a comment. Refuses, by line, non-numbers, times running
/// backwards and poses outside 0..bounds.travel_mm.
std::vector<PoseLogEntry> readPoseLog(const std::string& path, const RecordingBounds& bounds);

/// Writes `taps` as a dumper would have logged them (for yarpdataplayer, and to test the import):
/// `folder`/data.log with one frame per sample at sampleRate_hz, resting frames of zeros between
/// taps, the fingertip's values at the map's places in frames of map.valuesPerFrame (the rest 0),
/// stamps with six decimals as the dumper writes them; `folder`/info.log; and `folder`/poses.log
/// with each tap's start time and pose. Throws InputError if a file cannot be written.
void writeDumperLog(const std::string& folder, const std::vector<TapRecord>& taps,
                    const TaxelMap& map, double sampleRate_hz);

}  // namespace activetouch
