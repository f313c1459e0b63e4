#pragma once
// Quantiles and tail probabilities of the distributions the workbench's statistics use, exact to
// double precision, from Boost.Math (docs/design.md, "Statistics"). Every interval and test in the
// project takes its quantiles from here.
namespace activetouch::stats {

/// z with P(Z > z) = upperTail for the standard normal; 0 < upperTail < 1.
double normalUpper(double upperTail);
/// The two-sided z of a confidence level: normalUpper((1 - level) / 2); 1.96 at 0.95.
double normalTwoSided(double level = 0.95);
/// t with P(T > t) = upperTail for Student's t with `df` > 0 degrees of freedom.
double studentUpper(double df, double upperTail);
/// The two-sided t of a confidence level with `df` degrees of freedom; 2.262 at 9 and 0.95.
double studentTwoSided(double df, double level = 0.95);
/// x with P(X > x) = upperTail for chi-square with `df` > 0 degrees of freedom.
double chiSquareUpper(double df, double upperTail);
/// P(X <= k) for X ~ Binomial(n, p); 1 for k >= n, 0 for k < 0.
double binomialCdf(int k, int n, double p);
/// The lower quantile of Beta(a, b), a, b > 0, at probability p in [0, 1].
double betaQuantile(double a, double b, double p);

}  // namespace activetouch::stats
