#pragma once
// The recording of contour-following trials: every tap with its pose, time, samples, percept and
// decision, appended and flushed as it is taken, so a run that dies loses at most the tap in
// flight. Long format: one row per (tap, sample), one column per taxel.
#include <cstdio>
#include <string>

#include "core/control/ContourFollower.h"

namespace activetouch {

class FollowingRecording {
public:
    /// Opens (truncating) `path`; throws InputError if it cannot be written.
    FollowingRecording(const std::string& path, int taxels);
    ~FollowingRecording();
    FollowingRecording(const FollowingRecording&) = delete;
    FollowingRecording& operator=(const FollowingRecording&) = delete;

    void append(const std::string& label, FollowingMode mode, int trial, int tapIndex,
                const FollowedTap& tap);

private:
    std::FILE* file_ = nullptr;
    int taxels_;
};

}  // namespace activetouch
