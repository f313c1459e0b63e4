#pragma once
// A recorded trial replayed as a rig (docs/design.md §5: a recording can be replayed as a rig). The
// stage goes wherever it is sent; each tap is the recorded trial's next tap, served only if the
// stage stands where that tap was taken. A run with the recorded run's classifier, valid range
// and controller settings retraces the recording tap for tap; a run that decides otherwise
// leaves it, and the rig says where (RecordingLeft). The robot clock runs on the recorded tap
// times.
#include <string>

#include "core/records/FollowingRecording.h"
#include "core/rig/Rig.h"

namespace activetouch {

class ReplayRig final : private Stage, private Tapper, private TactileSensor, private RobotClock {
public:
    /// Poses closer than this to the recorded one are the same (the recording keeps 17 digits).
    static constexpr double kPoseTolerance_mm = 1e-6;

    /// Replays `trial` (not copied; must outlive the rig); `source` names the recording in
    /// messages.
    ReplayRig(const RecordedTrial& trial, std::string source);
    ReplayRig(const ReplayRig&) = delete;
    ReplayRig& operator=(const ReplayRig&) = delete;

    Rig rig() { return Rig{*this, *this, *this, *this}; }
    /// Taps served so far.
    int served() const { return next_; }

private:
    void moveTo(Vec2 target) override { pose_ = target; }
    Vec2 position() const override { return pose_; }
    TapRecord tap() override;
    int taxelCount() const override;
    void latestFrame(double* out) const override;
    double now_s() const override;

    const RecordedTrial& trial_;
    std::string source_;
    Vec2 pose_{};
    int next_ = 0;
};

}  // namespace activetouch
