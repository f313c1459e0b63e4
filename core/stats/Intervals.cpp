#include "core/stats/Intervals.h"

#include <algorithm>
#include <cmath>

#include "core/stats/Distributions.h"

namespace activetouch::stats {

Interval wilson(int count, int total, double level, double designEffect) {
    const double z = normalTwoSided(level), z2 = z * z;
    const double p = double(count) / total;
    const double n = designEffect > 1.0 ? total / designEffect : total;
    const double centre = (p + z2 / (2 * n)) / (1 + z2 / n);
    const double half = z * std::sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / (1 + z2 / n);
    return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

void ClusteredProportion::add(int count, int total) {
    if (total <= 0) return;
    count_ += count;
    total_ += total;
    ++clusters_;
    largest_ = std::max(largest_, total);
    const double c = count, n = total;
    countSquares_ += c * c;
    crossProducts_ += c * n;
    totalSquares_ += n * n;
}

double ClusteredProportion::designEffect() const {
    if (largest_ <= 1 || clusters_ < 2 || count_ <= 0 || count_ >= total_) return 1.0;
    const double n = total_, p = count_ / n, k = clusters_;
    // sum_i (c_i - p n_i)^2 from the running sums (whole numbers up to ~1e9: exact in doubles).
    const double spread =
        std::max(0.0, countSquares_ - 2.0 * p * crossProducts_ + p * p * totalSquares_);
    const double clustered = k / (k - 1.0) * spread / (n * n);
    return std::max(1.0, clustered / (p * (1.0 - p) / n));
}

Interval clopperPearson(int count, int total, double level) {
    const double tail = 0.5 * (1.0 - level);
    return {count == 0 ? 0.0 : betaQuantile(count, total - count + 1, tail),
            count == total ? 1.0 : betaQuantile(count + 1, total - count, 1.0 - tail)};
}

MeanInterval studentMean(const std::vector<double>& values, double least, double most,
                         double level) {
    MeanInterval e;
    const std::size_t n = values.size();
    if (n == 0) return e;
    double sum = 0.0;
    for (double v : values) sum += v;
    e.mean = sum / double(n);
    if (n == 1 || !std::isfinite(e.mean)) {
        e.low = n == 1 ? least : e.mean;
        e.high = n == 1 ? most : e.mean;
        return e;
    }
    double ss = 0.0;
    for (double v : values) ss += (v - e.mean) * (v - e.mean);
    const double t = studentTwoSided(double(n - 1), level);
    const double se = std::sqrt(ss / double(n - 1) / double(n));
    const bool below = std::isfinite(least), above = std::isfinite(most);
    if (below && above && e.mean > least && e.mean < most) {
        const double width = most - least, u = (e.mean - least) / width;
        const double centre = std::log(u / (1.0 - u)), half = t * se / (width * u * (1.0 - u));
        const auto back = [&](double x) { return least + width / (1.0 + std::exp(-x)); };
        e.low = back(centre - half);
        e.high = back(centre + half);
    } else if (below && !above && e.mean > least) {
        const double d = e.mean - least, factor = std::exp(t * se / d);
        e.low = least + d / factor;
        e.high = least + d * factor;
    } else {
        // Unbounded, or every value at its bound (then se is 0 and so is the width).
        e.low = std::max(least, e.mean - t * se);
        e.high = std::min(most, e.mean + t * se);
    }
    return e;
}

PairedDifference agrestiMinDifference(int onlyA, int onlyB, int pairs, double level) {
    PairedDifference r;
    r.difference = pairs > 0 ? double(onlyB - onlyA) / pairs : 0.0;
    const double n = pairs + 2.0, a = onlyA + 0.5, b = onlyB + 0.5;
    const double d = (b - a) / n;
    const double variance = std::max(0.0, (a + b) - (b - a) * (b - a) / n) / (n * n);
    const double half = normalTwoSided(level) * std::sqrt(variance);
    r.interval = {std::max(-1.0, d - half), std::min(1.0, d + half)};
    return r;
}

double mcnemarExactP(int onlyA, int onlyB) {
    const int n = onlyA + onlyB;
    if (n == 0) return 1.0;
    return std::min(1.0, 2.0 * binomialCdf(std::min(onlyA, onlyB), n, 0.5));
}

Interval percentileInterval(std::vector<double>& values, double level) {
    if (values.empty()) return {};
    std::sort(values.begin(), values.end(), [](double a, double b) {
        if (std::isnan(a)) return false;
        if (std::isnan(b)) return true;
        return a < b;
    });
    const std::size_t n = values.size();
    const auto at = [&](double q) {
        return values[std::min(n - 1,
                               static_cast<std::size_t>(std::floor(q * double(n - 1) + 0.5)))];
    };
    return {at(0.5 * (1.0 - level)), at(0.5 * (1.0 + level))};
}

double medianOr(std::vector<double> values, double ifEmpty) {
    if (values.empty()) return ifEmpty;
    std::sort(values.begin(), values.end());
    const std::size_t m = values.size() / 2;
    return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

}  // namespace activetouch::stats
