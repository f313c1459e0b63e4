// A fingertip's 12 values out of a hand's skin vector, and skinManager's compensation of raw
// values (YarpProtocol.h).
#include <algorithm>
#include <cmath>

#include "devices/yarp/YarpProtocol.h"

namespace activetouch::yarp {

std::vector<double> fingertipTaxels(const std::vector<double>& hand, Finger finger) {
    if (hand.size() != 192)
        throw YarpError("a hand skin vector has 192 values (16 patches x 12); this one has " +
                        std::to_string(hand.size()));
    const auto first = hand.begin() + static_cast<int>(finger);
    return std::vector<double>(first, first + 12);
}

void SkinCompensation::calibrate(const std::vector<double>& raw) {
    if (static_cast<int>(raw.size()) != taxels_)
        throw YarpError("a calibration frame has " + std::to_string(raw.size()) +
                        " taxels, expected " + std::to_string(taxels_));
    resting_.push_back(raw);
    finishCalibration();
}

void SkinCompensation::finishCalibration() {
    const auto K = static_cast<std::size_t>(taxels_);
    baseline_.assign(K, 0.0);
    threshold_.assign(K, 1.0);
    for (std::size_t k = 0; k < K; ++k) {
        std::vector<double> drop;
        for (const auto& f : resting_) drop.push_back(255.0 - f[k]);
        double mean = 0;
        for (double d : drop) mean += d;
        mean /= static_cast<double>(drop.size());
        baseline_[k] = mean;
        std::vector<double> deviation;
        for (double d : drop) deviation.push_back(std::abs(d - mean));
        std::sort(deviation.begin(), deviation.end());
        const double p95 = deviation[std::min(
            deviation.size() - 1,
            static_cast<std::size_t>(0.95 * static_cast<double>(deviation.size())))];
        threshold_[k] = std::max(1.0, p95);
    }
}

std::vector<double> SkinCompensation::compensate(const std::vector<double>& raw) {
    if (!calibrated())
        throw YarpError("the skin compensation is not calibrated; record resting frames first");
    if (static_cast<int>(raw.size()) != taxels_)
        throw YarpError("a skin frame has " + std::to_string(raw.size()) + " taxels, expected " +
                        std::to_string(taxels_));
    std::vector<double> out(raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k) {
        const double d = 255.0 - raw[k] - baseline_[k];
        const double gain = d > threshold_[k] ? 0.05 : 0.2;
        baseline_[k] += gain * 0.02 * d / threshold_[k];
        out[k] = std::clamp(d, 0.0, 255.0);
    }
    return out;
}

}  // namespace activetouch::yarp
