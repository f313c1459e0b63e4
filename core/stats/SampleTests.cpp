#include "core/stats/SampleTests.h"

#include <algorithm>
#include <cmath>

namespace activetouch::stats {

double ksDistance(std::vector<double> a, std::vector<double> b) {
    if (a.empty() || b.empty()) return std::nan("");
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    std::size_t i = 0, j = 0;
    double d = 0.0;
    while (i < a.size() && j < b.size()) {
        const double x = std::min(a[i], b[j]);
        while (i < a.size() && a[i] <= x) ++i;
        while (j < b.size() && b[j] <= x) ++j;
        d = std::max(
            d, std::abs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
    }
    return d;
}

double wasserstein(std::vector<double> a, std::vector<double> b) {
    // Between two empirical distributions: the mean gap of their quantiles.
    if (a.empty() || b.empty()) return std::nan("");
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    const std::size_t n = 1000;
    double sum = 0.0;
    for (std::size_t q = 0; q < n; ++q) {
        const double p = (q + 0.5) / n;
        sum += std::abs(a[static_cast<std::size_t>(p * a.size())] -
                        b[static_cast<std::size_t>(p * b.size())]);
    }
    return sum / n;
}

double cochranQ(const std::vector<double>& logs, const std::vector<double>& se) {
    double weightSum = 0.0, weighted = 0.0;
    for (std::size_t k = 0; k < logs.size(); ++k)
        if (se[k] > 0) {
            weightSum += 1.0 / (se[k] * se[k]);
            weighted += logs[k] / (se[k] * se[k]);
        }
    if (weightSum <= 0) return 0.0;
    const double centre = weighted / weightSum;
    double q = 0.0;
    for (std::size_t k = 0; k < logs.size(); ++k)
        if (se[k] > 0) {
            const double d = (logs[k] - centre) / se[k];
            q += d * d;
        }
    return q;
}

}  // namespace activetouch::stats
