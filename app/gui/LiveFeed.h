#pragma once
// The latest tap and frame, handed from whichever thread drives the rig to the GUI. Writers
// publish; the GUI's timer takes the newest state at its own pace (data never drives a replot).
#include <QMetaType>
#include <QString>
#include <mutex>

#include "core/tap/Tap.h"

namespace activetouch {

class LiveFeed {
public:
    struct Snapshot {
        Tap tap;                    ///< the most recent complete tap
        std::vector<double> frame;  ///< the most recent frame (may run ahead of `tap` when paced)
        Vec2 pose;
        QString what;            ///< what the tap was, in a sentence
        bool perceived = false;  ///< a following tap: `what` says its percept
        std::uint64_t tapSerial = 0;
        std::uint64_t frameSerial = 0;
    };

    void publishTap(const TapRecord& record, const QString& what, bool perceived) {
        std::lock_guard lock(mutex_);
        state_.tap = record.tap;
        state_.pose = record.pose;
        state_.what = what;
        state_.perceived = perceived;
        ++state_.tapSerial;
    }
    void publishFrame(const double* frame, int taxels) {
        std::lock_guard lock(mutex_);
        state_.frame.assign(frame, frame + taxels);
        ++state_.frameSerial;
    }
    Snapshot snapshot() const {
        std::lock_guard lock(mutex_);
        return state_;
    }
    std::uint64_t tapSerial() const {
        std::lock_guard lock(mutex_);
        return state_.tapSerial;
    }

private:
    mutable std::mutex mutex_;
    Snapshot state_;
};

}  // namespace activetouch
