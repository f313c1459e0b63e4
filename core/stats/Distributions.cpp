#include "core/stats/Distributions.h"

#include <boost/math/distributions/beta.hpp>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace activetouch::stats {

namespace bm = boost::math;

double normalUpper(double upperTail) {
    return bm::quantile(bm::complement(bm::normal_distribution<double>(), upperTail));
}

double normalTwoSided(double level) {
    return normalUpper(0.5 * (1.0 - level));
}

double studentUpper(double df, double upperTail) {
    return bm::quantile(bm::complement(bm::students_t_distribution<double>(df), upperTail));
}

double studentTwoSided(double df, double level) {
    return studentUpper(df, 0.5 * (1.0 - level));
}

double chiSquareUpper(double df, double upperTail) {
    return bm::quantile(bm::complement(bm::chi_squared_distribution<double>(df), upperTail));
}

double binomialCdf(int k, int n, double p) {
    if (k < 0) return 0.0;
    if (k >= n) return 1.0;
    return bm::cdf(bm::binomial_distribution<double>(n, p), k);
}

double betaQuantile(double a, double b, double p) {
    return bm::quantile(bm::beta_distribution<double>(a, b), p);
}

}  // namespace activetouch::stats
