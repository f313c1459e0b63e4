// Goodness of fit that speaks up (docs/calibration.md): statistics the fit did not use, read on
// the recording and on twenty recordings simulated with the fitted scene at the same poses. Where
// the recording lies more than kFar standard deviations from the simulated ones (and outside their
// range), the fit names what the recording shows that its scene does not model.
#include <algorithm>
#include <cmath>

#include "devices/simulated/fit/FitSteps.h"

namespace activetouch::scenefit {

namespace {

/// Far enough that twenty clean fits of three statistics almost never speak up (a normal tail of
/// 6e-5 each), near enough that a saturation or a drift compensated otherwise stands out.
constexpr double kFar = 4.0;

/// Readings above this many counts are pressed, for the pile statistic.
constexpr double kPressed = 10.0;

/// Per taxel, the share of its pressed readings that sit at its highest value (within half a
/// count), averaged over the taxels that are pressed: a saturation piles them there.
double pileAtTop(const std::vector<TapRecord>& taps, int taxels, const std::vector<char>& skip) {
    double sum = 0.0;
    int counted = 0;
    for (int k = 0; k < taxels; ++k) {
        if (skip[std::size_t(k)]) continue;
        const std::vector<double> v = readings(taps, k);
        const double top = *std::max_element(v.begin(), v.end());
        long pressed = 0, atTop = 0;
        for (double x : v) {
            pressed += x > kPressed;
            atTop += x > kPressed && x >= top - 0.5;
        }
        if (pressed < 20) continue;
        sum += static_cast<double>(atTop) / static_cast<double>(pressed);
        ++counted;
    }
    return counted > 0 ? sum / counted : 0.0;
}

/// The 99.5th percentile of every live taxel's readings: the upper tail of the pressures.
double upperTail(const std::vector<TapRecord>& taps, int taxels, const std::vector<char>& skip) {
    std::vector<double> all;
    for (int k = 0; k < taxels; ++k)
        if (!skip[std::size_t(k)]) {
            const std::vector<double> v = readings(taps, k);
            all.insert(all.end(), v.begin(), v.end());
        }
    if (all.empty()) return 0.0;
    const auto at = static_cast<std::ptrdiff_t>(0.995 * static_cast<double>(all.size() - 1));
    std::nth_element(all.begin(), all.begin() + at, all.end());
    return all[std::size_t(at)];
}

/// The autocorrelation ten taps apart of the resting level: each tap's mean over its live taxels
/// of the first samples, taken in the air before the tip reaches anything. A compensated drift
/// forgets within a few taps; a drift left alone does not.
double restingPersistence(const std::vector<TapRecord>& taps, int taxels,
                          const std::vector<char>& skip) {
    std::vector<double> level;
    for (const TapRecord& r : taps) {
        const int first = std::min(3, r.tap.sampleCount());
        double sum = 0.0;
        int n = 0;
        for (int t = 0; t < first; ++t)
            for (int k = 0; k < taxels; ++k)
                if (!skip[std::size_t(k)]) sum += r.tap.at(t, k), ++n;
        level.push_back(n > 0 ? sum / n : 0.0);
    }
    constexpr std::size_t kLag = 10;
    if (level.size() < 2 * kLag) return 0.0;
    const double m = meanOf(level);
    double num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < level.size(); ++i) {
        den += (level[i] - m) * (level[i] - m);
        if (i >= kLag) num += (level[i] - m) * (level[i - kLag] - m);
    }
    return den > 0.0 ? num / den : 0.0;
}

/// Over the (tap, taxel) pairs whose press reached the taxel's highest value in the recording:
/// how much of that value the tap's last five samples still read, after the release. A taxel
/// that saturates and recovers slowly holds it; a converter that only clips does not.
double heldAfterTop(const std::vector<TapRecord>& taps, int taxels, const std::vector<char>& skip) {
    double held = 0.0, top = 0.0;
    for (int k = 0; k < taxels; ++k) {
        if (skip[std::size_t(k)]) continue;
        double highest = 0.0;
        for (const TapRecord& r : taps)
            for (int t = 0; t < r.tap.sampleCount(); ++t)
                highest = std::max(highest, r.tap.at(t, k));
        if (highest <= kPressed) continue;
        for (const TapRecord& r : taps) {
            const int n = r.tap.sampleCount();
            double most = 0.0;
            for (int t = 0; t < n; ++t) most = std::max(most, r.tap.at(t, k));
            if (most < highest - 0.5 || n < 5) continue;
            for (int t = n - 5; t < n; ++t) held += r.tap.at(t, k) / 5.0;
            top += most;
        }
    }
    return top > 0.0 ? held / top : 0.0;
}

struct Statistic {
    const char* name;
    double (*of)(const std::vector<TapRecord>&, int, const std::vector<char>&);
    const char* higher;  ///< what a recording far above the simulated ones suggests
    const char* lower;   ///< far below
};

const Statistic kStatistics[] = {
    {"readings piled at each taxel's highest value", pileAtTop,
     "the taxels saturate below the converter's top, which the fitted scene does not model "
     "(saturation_recovery lists such a level)",
     "the readings spread more at the top than the fitted scene's"},
    {"the upper tail of the pressures (99.5th percentile, counts)", upperTail,
     "the strongest presses read higher than the fitted scene's: more sensitive skin or a deeper "
     "stroke than the scene's tapper",
     "the strongest presses are cut short: the taxels saturate below the converter's top "
     "(saturation_recovery lists such a level, which the fitted scene does not model), or the "
     "stroke is shallower than the scene's tapper"},
    {"readings held after a press that reached a taxel's highest value (share of it in the "
     "tap's last five samples)",
     heldAfterTop,
     "taxels that reach their top recover from it slowly: a saturation with a recovery "
     "(saturation_recovery), which the fitted scene does not model",
     "presses that reach the top let go faster than the fitted scene's memory"},
    {"the resting level's persistence from tap to tap (autocorrelation ten taps apart)",
     restingPersistence,
     "the baseline wanders from tap to tap more persistently than the fitted drift does: a drift "
     "compensated otherwise than baseline_drift's gains (which this fit keeps from the base "
     "scene), or not at all",
     "the baseline returns faster than the fitted drift: a stronger compensation than "
     "baseline_drift's gains"},
};

}  // namespace

void lookForUnmodelled(const FitRun& run, const std::vector<TapRecord>& recorded, SceneFit& fit) {
    const int taxels = run.taxels();
    const std::vector<char>& skip = run.c.skip;
    for (const Statistic& s : kStatistics) {
        std::vector<double> simulated;
        for (const auto& sim : fit.simulated) simulated.push_back(s.of(sim, taxels, skip));
        const double value = s.of(recorded, taxels, skip);
        const double m = meanOf(simulated);
        const double spread = std::max(sd(simulated), 1e-3 * std::abs(m) + 1e-9);
        const auto [least, largest] = std::minmax_element(simulated.begin(), simulated.end());
        const double z = (value - m) / spread;
        if (std::abs(z) <= kFar || (value >= *least && value <= *largest)) continue;
        fit.unmodelled.push_back(
            {s.name, value, m, *least, *largest, z, z > 0 ? s.higher : s.lower});
    }
}

}  // namespace activetouch::scenefit
