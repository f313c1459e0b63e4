#pragma once
// The median of a list of values, for the figures runs report.
#include <algorithm>
#include <vector>

namespace activetouch {

/// The median of `values` (the mean of the middle two for an even count), or `ifEmpty`.
inline double medianOr(std::vector<double> values, double ifEmpty) {
    if (values.empty()) return ifEmpty;
    std::sort(values.begin(), values.end());
    const std::size_t m = values.size() / 2;
    return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

}  // namespace activetouch
