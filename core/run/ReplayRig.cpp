#include "core/run/ReplayRig.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace activetouch {

ReplayRig::ReplayRig(const RecordedTrial& trial, std::string source)
    : trial_(trial), source_(std::move(source)) {}

TapRecord ReplayRig::tap() {
    // Taps are numbered from 0, as in following_taps.csv.
    const int count = static_cast<int>(trial_.taps.size());
    char buf[320];
    // Named only when the replay leaves the recording.
    const auto which = [&] {
        return "the recorded " + std::string(modeName(trial_.mode)) + " " + trial_.label +
               " trial " + std::to_string(trial_.trial) + " (" + source_ + ")";
    };
    if (next_ >= count) {
        if (count == 0) throw RecordingLeft(which() + " holds no tap");
        std::snprintf(buf, sizeof buf,
                      " ends after tap %d; the replay went on to tap %d at (%.2f, %.2f) mm",
                      count - 1, next_, pose_.x, pose_.y);
        throw RecordingLeft(which() + buf);
    }
    const TapRecord& recorded = trial_.taps[static_cast<std::size_t>(next_)];
    const double off = distance(recorded.pose, pose_);
    if (off > kPoseTolerance_mm) {
        if (next_ == 0)
            std::snprintf(buf, sizeof buf,
                          " starts at (%.2f, %.2f) mm; the replay started at (%.2f, %.2f) mm, "
                          "%.2f mm away (a trial starts centred in the valid range)",
                          recorded.pose.x, recorded.pose.y, pose_.x, pose_.y, off);
        else
            std::snprintf(buf, sizeof buf,
                          " took tap %d at (%.2f, %.2f) mm; the replay asked for it at (%.2f, "
                          "%.2f) mm, %.2f mm away",
                          next_, recorded.pose.x, recorded.pose.y, pose_.x, pose_.y, off);
        throw RecordingLeft(which() + buf);
    }
    ++next_;
    return recorded;
}

int ReplayRig::taxelCount() const {
    return trial_.taps.empty() ? kFingertipTaxels : trial_.taps.front().tap.taxels;
}

void ReplayRig::latestFrame(double* out) const {
    const int k = taxelCount();
    if (next_ == 0) {
        std::fill(out, out + k, 0.0);
        return;
    }
    const Tap& last = trial_.taps[static_cast<std::size_t>(next_ - 1)].tap;
    std::copy(last.frame(last.sampleCount() - 1), last.frame(last.sampleCount() - 1) + k, out);
}

double ReplayRig::now_s() const {
    // Before the first tap: its start. After a tap: the next recorded tap's start (when this
    // one's cycle ended), or for the last one its start plus the trial's mean cycle.
    const auto& taps = trial_.taps;
    if (taps.empty()) return 0.0;
    if (next_ < static_cast<int>(taps.size()))
        return taps[static_cast<std::size_t>(next_)].startTime_s;
    const double span = taps.back().startTime_s - taps.front().startTime_s;
    const double cycle = taps.size() > 1 ? span / static_cast<double>(taps.size() - 1) : 0.0;
    return taps.back().startTime_s + cycle;
}

}  // namespace activetouch
