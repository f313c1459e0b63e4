#pragma once
// What real fingertips' frames say of their taxels where the poses are unknown
// (docs/real-fingertips.md): per finger and taxel the resting offset, the noise, the quantisation
// step, the drift over a recording, dead and stuck taxels, the range reached under contact, and
// the fingers' common movement at rest, each with an interval over the recordings (each
// recording, a grasp, is one independent unit).
#include <string>
#include <vector>

#include "core/records/FramesImport.h"
#include "core/stats/Intervals.h"

namespace activetouch {

struct TaxelStats {
    std::string finger;
    int taxel = 0;
    int restFrames = 0, contactFrames = 0;
    stats::MeanInterval offset;  ///< resting pressure, counts: the mean of each recording's mean
    stats::MeanInterval sigma;   ///< resting standard deviation within a recording, counts
    double quantum = 0.0;        ///< the smallest step between two readings seen, counts
    stats::MeanInterval drift;   ///< resting level's change from a recording's first to last third
    bool dead = false;           ///< reads no pressure in any frame
    bool stuck = false;          ///< one reading, not zero, in every frame
    double maxPressure = 0.0;    ///< the most it read, counts
    /// The 99th percentile under contact, counts, with a 95 % interval from resampling the
    /// recordings (200 resamples).
    double contactP99 = 0.0, contactP99Low = 0.0, contactP99High = 0.0;
    double atFullScale = 0.0;  ///< share of its readings at the converter's full scale
    /// Its resting frames as a compensated fingertip reports them: each above its recording's
    /// resting level (the rest mean, rounded to the converter's step), clipped at 0.
    std::vector<double> restAbove;
    /// Its readings in frames not at rest, above the same level (clipped at 0): under contact.
    std::vector<double> contactAbove;
};

struct FingerStats {
    std::string finger;
    int taxels = 0;
    /// The mean correlation of pairs of its taxels' resting deviations: common-mode noise or
    /// crosstalk where it is well above 0.
    stats::MeanInterval restCorrelation;
};

struct FingertipStatsReport {
    std::vector<TaxelStats> taxels;
    std::vector<FingerStats> fingers;
    int files = 0, frames = 0;
    /// A frame is at rest for a finger when each of its taxels reads within this many counts of
    /// its resting level in that recording (its 10th percentile).
    double restMargin = 3.0;
};

FingertipStatsReport fingertipStats(const FramesImport& frames, double restMargin = 3.0);

}  // namespace activetouch
