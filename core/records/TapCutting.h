#pragma once
// A skin stream cut into taps, and the taps labelled with the training protocol that took them:
// how a dumper log (DumperLog.h) becomes the project's tap recording.
#include <string>
#include <vector>

#include "core/records/DumperLog.h"

namespace activetouch {

/// How a stream is cut into taps.
struct TapCutting {
    int samplesPerTap = kSamplesPerTap;
    double sampleRate_hz = kSampleRateHz;
    /// The reflex threshold: total pressure over the fingertip's taxels, counts. A tap whose
    /// window reaches it ended on the reflex; one that never does, at the stroke limit.
    double reflexThreshold = 40.0;
    /// Without a pose log, a tap's window starts this many frames before the frame that crosses
    /// the threshold (the descent to the surface).
    int leadFrames = 4;
};

/// The taps in `stream`. With `poses`, one per pose line: the window is the samplesPerTap frames
/// from the first frame stamped at or after the line's time (less half a period), and the tap's
/// pose and start time are the line's. Without, one per rising crossing of the reflex threshold,
/// its window starting leadFrames before it (taps that never touch leave no trace and are not
/// found). A window with a frame missing (a counter gap or a stamp gap over 1.5 periods) is
/// refused naming its lines; a last window cut short by the end of the log is left out and
/// `cutOff` says so (without `cutOff` it is refused).
std::vector<TapRecord> cutTaps(const SkinStream& stream, const std::vector<PoseLogEntry>* poses,
                               const TapCutting& cutting, const std::string& logPath,
                               const std::string& poseLogPath, std::string* cutOff = nullptr);

/// Labels cut taps with the training protocol that took them: the k-th tap is the protocol's
/// k-th (data set, class, repeat), in the order collectTrainingTaps takes them. With poses from
/// a log, each must lie within `tolerance_mm` plus four standard deviations of the placement
/// jitter of the protocol's pose for it (else the log is of another experiment or out of order,
/// refused naming the pose log's line), and its true offset is its distance from the edge.
/// Without, the protocol's commanded pose and offset are used. More taps than the protocol takes
/// are refused.
std::vector<CollectedTap> labelProtocolTaps(const std::vector<TapRecord>& taps, bool posesLogged,
                                            const std::vector<PoseLogEntry>& poseLines,
                                            const Polygon& object, const ClassSet& classes,
                                            const TrainingProtocolSettings& protocol,
                                            const std::string& poseLogPath,
                                            const std::string& logPath, double tolerance_mm = 0.25);

}  // namespace activetouch
