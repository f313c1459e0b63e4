#pragma once
// Confidence intervals and tests for what the workbench reports (docs/design.md, "Statistics"):
// a proportion (Wilson, or Clopper-Pearson where an exact interval is wanted), a mean over seeds
// (Student's t, optionally on a scale that respects the quantity's bounds), a paired difference of
// proportions (Agresti-Min) with McNemar's exact test, and a percentile interval of resampled
// values. Levels are two-sided; the default is 95 %.
#include <vector>

namespace activetouch::stats {

struct Interval {
    double low = 0.0, high = 0.0;
};

/// Wilson's score interval for `count` of `total` (total > 0), within [0, 1]. With a design
/// effect above 1 (clustered draws, ClusteredProportion), on the effective total: the same
/// rate from total / designEffect independent draws (Kish).
Interval wilson(int count, int total, double level = 0.95, double designEffect = 1.0);

/// A proportion pooled over clusters, each adding its count of its total: draws within a
/// cluster (the trials of one seed, which share its training run) need not be independent. Its
/// design effect is the pooled rate's variance with the clusters as the independent units (the
/// ratio estimator's linearised variance, k / (k - 1) sum_i (c_i - p n_i)^2 / n^2) over the
/// binomial p (1 - p) / n; at least 1, so that an interval on it is never narrower than the
/// binomial one, and exactly 1 where every cluster has at most one draw (then they are the
/// independent draws), fewer than two clusters have any, or the rate is 0 or 1. Kept as running
/// sums: adding a cluster is O(1).
class ClusteredProportion {
public:
    void add(int count, int total);
    int count() const { return count_; }
    int total() const { return total_; }
    double designEffect() const;

private:
    int count_ = 0, total_ = 0, clusters_ = 0, largest_ = 0;
    double countSquares_ = 0.0, crossProducts_ = 0.0, totalSquares_ = 0.0;
};
/// Clopper and Pearson's exact interval for `count` of `total` (total > 0).
Interval clopperPearson(int count, int total, double level = 0.95);

/// A mean with its interval.
struct MeanInterval {
    double mean = 0.0, low = 0.0, high = 0.0;
};

/// The mean of `values` with Student's t interval (n - 1 degrees of freedom). A quantity bounded
/// by [least, most] (either may be infinite) has its interval computed where it cannot cross a
/// bound, by the delta method: on the logit scale of its place in a two-sided range, on the log
/// scale of its distance from a single bound; never cut at the bound. With one value the interval
/// is [least, most]; with none, all zero; a non-finite mean gives itself as both ends.
MeanInterval studentMean(const std::vector<double>& values, double least, double most,
                         double level = 0.95);

/// A paired difference of proportions, (onlyB - onlyA) / pairs, with Agresti and Min's (2005)
/// interval (half a pair added to each discordant cell), within [-1, 1].
struct PairedDifference {
    double difference = 0.0;
    Interval interval;
};
PairedDifference agrestiMinDifference(int onlyA, int onlyB, int pairs, double level = 0.95);

/// McNemar's exact two-sided p for `onlyA` and `onlyB` discordant pairs: twice the smaller
/// binomial tail at one half, at most 1.
double mcnemarExactP(int onlyA, int onlyB);

/// The percentile interval of `values` (sorted in place; NaN sorts last): the values at the
/// (1 - level) / 2 and (1 + level) / 2 places, each rounded to the nearest rank.
Interval percentileInterval(std::vector<double>& values, double level = 0.95);

/// The median of `values` (the mean of the middle two for an even count), or `ifEmpty`.
double medianOr(std::vector<double> values, double ifEmpty);

}  // namespace activetouch::stats
