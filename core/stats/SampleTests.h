#pragma once
// Distances between two samples and a test of their agreement, as the calibration's goodness of
// fit reads them: the Kolmogorov-Smirnov distance, the first Wasserstein distance, and Cochran's
// Q over estimates with their standard errors.
#include <vector>

namespace activetouch::stats {

/// The Kolmogorov-Smirnov distance between the empirical distributions of `a` and `b`: the
/// largest gap between their cumulative shares. NaN if either is empty.
double ksDistance(std::vector<double> a, std::vector<double> b);

/// The first Wasserstein distance between the empirical distributions of `a` and `b`, as the mean
/// gap of their quantiles at 1000 evenly spaced levels. NaN if either is empty.
double wasserstein(std::vector<double> a, std::vector<double> b);

/// Cochran's Q of `logs` about their inverse-variance weighted mean, over the entries whose
/// standard error `se` is positive (so that one read loosely moves the centre little); 0 for
/// none.
double cochranQ(const std::vector<double>& logs, const std::vector<double>& se);

}  // namespace activetouch::stats
