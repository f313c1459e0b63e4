// Readings of taps, and the small summaries the estimators take of them.
#include "devices/simulated/fit/FitParts.h"

namespace activetouch::scenefit {

std::vector<double> readings(const std::vector<TapRecord>& taps, int k) {
    std::vector<double> v;
    for (const auto& r : taps)
        for (int t = 0; t < r.tap.sampleCount(); ++t) v.push_back(r.tap.at(t, k));
    return v;
}

double meanOf(const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double sd(const std::vector<double>& v) {
    if (v.size() < 2) return 0.0;
    const double m = meanOf(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / (v.size() - 1));
}

double zAbove(double value, const std::vector<double>& nulls) {
    const double spread = sd(nulls);
    const double expected = meanOf(nulls);
    return spread > 0 ? (value - expected) / spread : (value > expected ? 1e9 : 0.0);
}

}  // namespace activetouch::scenefit
