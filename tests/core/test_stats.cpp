// The statistics module (core/stats) against reference values: quantiles as R 4 prints them
// (qnorm, qt, qchisq, qbeta, pbinom; the same to the digits quoted in SciPy's norm.isf, t.isf,
// chi2.isf, beta.ppf, binom.cdf), intervals as R's prop.test(correct = FALSE) and binom.test give
// them, and the degenerate inputs every caller can hand it.
#include <QtTest>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/stats/Distributions.h"
#include "core/stats/Intervals.h"
#include "core/stats/Resampling.h"
#include "core/stats/SampleTests.h"

using namespace activetouch::stats;

namespace {
bool near(double a, double b, double tolerance = 1e-12) {
    return std::abs(a - b) <= tolerance * std::max(1.0, std::abs(b));
}
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

class TestStats : public QObject {
    Q_OBJECT

private slots:
    void quantilesAreRs() {
        QVERIFY(near(normalTwoSided(0.95), 1.959963984540054));  // qnorm(0.975)
        QVERIFY(near(normalUpper(0.001), 3.090232306167813));    // qnorm(0.999)
        QVERIFY(near(normalUpper(0.5), 0.0, 1e-15));
        // qt(0.975, 2), which for 2 degrees of freedom is (2p - 1) / sqrt(2p(1 - p)) in closed
        // form.
        QVERIFY(near(studentTwoSided(2), 0.95 / std::sqrt(2 * 0.975 * 0.025)));
        QVERIFY(near(studentTwoSided(9), 2.262157162798205));         // qt(0.975, 9)
        QVERIFY(near(studentTwoSided(30), 2.042272456301238));        // qt(0.975, 30)
        QVERIFY(near(studentTwoSided(100), 1.983971518523552));       // qt(0.975, 100)
        QVERIFY(near(chiSquareUpper(1, 0.05), 3.841458820694124));    // qchisq(0.95, 1)
        QVERIFY(near(chiSquareUpper(3, 0.05), 7.814727903251178));    // qchisq(0.95, 3)
        QVERIFY(near(chiSquareUpper(10, 0.001), 29.58829844507442));  // qchisq(0.999, 10)
        QVERIFY(near(betaQuantile(8, 3, 0.025), 0.4439045, 1e-7));    // qbeta(0.025, 8, 3)
        QCOMPARE(binomialCdf(2, 10, 0.5), 56.0 / 1024.0);             // pbinom(2, 10, 0.5)
        QCOMPARE(binomialCdf(-1, 10, 0.5), 0.0);
        QCOMPARE(binomialCdf(10, 10, 0.5), 1.0);
    }

    void proportionIntervalsAreRs() {
        // prop.test(8, 10, correct = FALSE)$conf.int
        const Interval w = wilson(8, 10);
        QVERIFY(near(w.low, 0.4901624715366418, 1e-12) && near(w.high, 0.9433178485456247, 1e-12));
        // binom.test(8, 10)$conf.int
        const Interval cp = clopperPearson(8, 10);
        QVERIFY(near(cp.low, 0.4439045, 1e-7) && near(cp.high, 0.9747893, 1e-7));
        // At the ends they stay inside [0, 1]: 0 of 20 and 20 of 20.
        QCOMPARE(clopperPearson(0, 20).low, 0.0);
        QVERIFY(
            near(clopperPearson(0, 20).high, 1.0 - std::pow(0.025, 1.0 / 20.0)));  // closed form
        QCOMPARE(clopperPearson(20, 20).high, 1.0);
        QCOMPARE(wilson(0, 20).low, 0.0);
        QCOMPARE(wilson(20, 20).high, 1.0);
    }

    void pooledRatesCountEachClusterAsOneUnit() {
        // Draws one to a cluster are the independent draws: the binomial interval, bit for bit.
        ClusteredProportion single;
        for (int i = 0; i < 40; ++i) single.add(i % 5 == 0 ? 0 : 1, 1);
        QCOMPARE(single.designEffect(), 1.0);
        QCOMPARE(wilson(single.count(), single.total(), 0.95, single.designEffect()).low,
                 wilson(32, 40).low);
        // Clusters alike (each 3 of 4): no spread between them, never narrower than binomial.
        ClusteredProportion alike;
        for (int i = 0; i < 30; ++i) alike.add(3, 4);
        QCOMPARE(alike.designEffect(), 1.0);
        // All or nothing, eight to a cluster: the clusters are the draws. The design effect is
        // 8 k / (k - 1), and the interval that of k - 1 independent clusters.
        ClusteredProportion whole;
        const int k = 50;
        for (int i = 0; i < k; ++i) whole.add(i < 35 ? 8 : 0, 8);
        QVERIFY(near(whole.designEffect(), 8.0 * k / (k - 1)));
        const Interval w = wilson(whole.count(), whole.total(), 0.95, whole.designEffect());
        const double q = 35.0 / 50.0, z = 1.959963984540054, n = k - 1;
        const double centre = (q + z * z / (2 * n)) / (1 + z * z / n);
        const double half = z * std::sqrt(q * (1 - q) / n + z * z / (4 * n * n)) / (1 + z * z / n);
        QVERIFY(near(w.low, centre - half, 1e-9) && near(w.high, centre + half, 1e-9));
        // Nothing to spread: a rate of 0 or 1, one cluster, or none.
        ClusteredProportion none, one, allRight;
        one.add(3, 8);
        for (int i = 0; i < 5; ++i) allRight.add(4, 4);
        QCOMPARE(none.designEffect(), 1.0);
        QCOMPARE(one.designEffect(), 1.0);
        QCOMPARE(allRight.designEffect(), 1.0);
        // Clusters of nothing count for nothing.
        ClusteredProportion withEmpty = whole;
        withEmpty.add(0, 0);
        QCOMPARE(withEmpty.designEffect(), whole.designEffect());
    }

    void pooledIntervalsCoverClusteredRatesAsOftenAsTheySay() {
        // Seeds of 8 trials whose success chance varies from seed to seed (a beta of mean 0.9,
        // as a training draw makes some runs worse than others): over 2000 repeats of 200 seeds,
        // the clustered interval holds the true rate about 95 % of the time; the binomial one,
        // counting trials as independent, markedly less often.
        std::mt19937_64 rng(2024);
        std::gamma_distribution<double> a(3.6, 1.0), b(0.4, 1.0);
        int clustered = 0, binomial = 0;
        const int repeats = 2000;
        for (int r = 0; r < repeats; ++r) {
            ClusteredProportion pooled;
            for (int seed = 0; seed < 200; ++seed) {
                const double x = a(rng), y = b(rng), chance = x / (x + y);
                std::binomial_distribution<int> trials(8, chance);
                pooled.add(trials(rng), 8);
            }
            const Interval c = wilson(pooled.count(), pooled.total(), 0.95, pooled.designEffect());
            const Interval w = wilson(pooled.count(), pooled.total());
            clustered += c.low <= 0.9 && 0.9 <= c.high;
            binomial += w.low <= 0.9 && 0.9 <= w.high;
        }
        qInfo("coverage of 0.9 over %d repeats: clustered %.3f, binomial %.3f", repeats,
              double(clustered) / repeats, double(binomial) / repeats);
        QVERIFY(clustered >= 0.93 * repeats && clustered <= 0.97 * repeats);
        QVERIFY(binomial < 0.85 * repeats);
    }

    void meansOverSeedsUseStudentsTInsideTheirBounds() {
        const MeanInterval three = studentMean({1.0, 2.0, 3.0}, -kInf, kInf);
        QCOMPARE(three.mean, 2.0);
        const double t2 = 0.95 / std::sqrt(2 * 0.975 * 0.025);  // qt(0.975, 2)
        QVERIFY(near(three.high, 2.0 + t2 / std::sqrt(3.0)));
        QVERIFY(near(three.low, 2.0 - t2 / std::sqrt(3.0)));
        // Bounded below: the log scale of the distance from the bound, never cut at it.
        const MeanInterval e = studentMean({0.1, 0.2, 0.15, 5.0}, 0.0, kInf);
        QVERIFY(e.low > 0.0 && e.low < e.mean && e.high > e.mean);
        const double d = e.mean, se = std::sqrt((std::pow(0.1 - d, 2) + std::pow(0.2 - d, 2) +
                                                 std::pow(0.15 - d, 2) + std::pow(5.0 - d, 2)) /
                                                3.0 / 4.0);
        QVERIFY(near(e.high, d * std::exp(3.182446305284263 * se / d), 1e-9));  // qt(0.975, 3)
        // Bounded on both sides: the logit scale.
        const MeanInterval f = studentMean({1.0, 1.0, 0.9, 1.0, 0.5}, 0.0, 1.0);
        QVERIFY(f.low > 0.0 && f.high < 1.0 && f.low < f.mean && f.mean < f.high);
        // Degenerate inputs: none, one, every value at its bound, identical values, a NaN.
        const MeanInterval none = studentMean({}, 0.0, kInf);
        QVERIFY(none.mean == 0.0 && none.low == 0.0 && none.high == 0.0);
        const MeanInterval one = studentMean({2.0}, 0.0, 5.0);
        QVERIFY(one.mean == 2.0 && one.low == 0.0 && one.high == 5.0);
        const MeanInterval zeros = studentMean({0.0, 0.0, 0.0}, 0.0, kInf);
        QVERIFY(zeros.mean == 0.0 && zeros.low == 0.0 && zeros.high == 0.0);
        const MeanInterval flat = studentMean(std::vector<double>(100, 0.25), -kInf, kInf);
        QVERIFY(flat.low == 0.25 && flat.high == 0.25);
        const MeanInterval bad = studentMean({1.0, std::nan("")}, 0.0, kInf);
        QVERIFY(std::isnan(bad.mean) && std::isnan(bad.low) && std::isnan(bad.high));
    }

    void pairedDifferencesAndMcNemar() {
        // 2 pairs only A got right, 8 only B, of 50: Agresti-Min's centre (8.5 - 2.5) / 52 and
        // half-width 1.96 * sqrt((11 - 36 / 52) / 52^2).
        const PairedDifference p = agrestiMinDifference(2, 8, 50);
        QVERIFY(near(p.difference, 6.0 / 50.0));
        const double centre = 6.0 / 52.0,
                     half = 1.959963984540054 * std::sqrt((11.0 - 36.0 / 52.0) / (52.0 * 52.0));
        QVERIFY(near(p.interval.low, centre - half) && near(p.interval.high, centre + half));
        // None discordant: a symmetric interval about 0, never empty.
        const PairedDifference none = agrestiMinDifference(0, 0, 100);
        QVERIFY(none.interval.low < 0 && none.interval.high > 0);
        // McNemar exact: mcnemar.exact / binom.test(1, 10)$p.value = 2 * 11 / 1024.
        QCOMPARE(mcnemarExactP(1, 9), 22.0 / 1024.0);
        QCOMPARE(mcnemarExactP(9, 1), 22.0 / 1024.0);
        QCOMPARE(mcnemarExactP(5, 5), 1.0);
        QCOMPARE(mcnemarExactP(0, 0), 1.0);
        // Thousands of discordant pairs stay finite (no factorials).
        const double p2 = mcnemarExactP(4000, 4200);
        QVERIFY(std::isfinite(p2) && p2 > 0.0 && p2 < 0.05);
    }

    void sampleDistancesAndCochransQ() {
        // Two samples of four, shifted by two: the cumulative shares differ by a half at most
        // (ks.test(1:4, 3:6)$statistic = 0.5); every quantile moves by 2.
        QCOMPARE(ksDistance({1, 2, 3, 4}, {3, 4, 5, 6}), 0.5);
        QCOMPARE(ksDistance({1, 2, 3}, {1, 2, 3}), 0.0);
        QCOMPARE(ksDistance({1, 2}, {5, 6}), 1.0);
        QVERIFY(near(wasserstein({1, 2, 3, 4}, {3, 4, 5, 6}), 2.0));
        QCOMPARE(wasserstein({0.5}, {0.5}), 0.0);
        // Empty samples have no distance: NaN, never a crash or a 0 that reads as "the same".
        QVERIFY(std::isnan(ksDistance({}, {1.0})) && std::isnan(wasserstein({1.0}, {})));
        // Q of 0 and 1 with unit errors about their mean 0.5: 0.25 + 0.25; a zero error is left
        // out; none left gives 0.
        QVERIFY(near(cochranQ({0.0, 1.0}, {1.0, 1.0}), 0.5));
        QVERIFY(near(cochranQ({0.0, 1.0, 9.0}, {1.0, 1.0, 0.0}), 0.5));
        QCOMPARE(cochranQ({1.0}, {0.0}), 0.0);
    }

    void resamplingIsTheSameOnEveryMachine() {
        // The generator's first draws from its fixed seed, as stated in Resampling.h.
        ResamplingGenerator g(0x5eed5eedULL);
        std::vector<std::size_t> draws;
        for (int i = 0; i < 4; ++i) draws.push_back(g.below(1000));
        ResamplingGenerator again(0x5eed5eedULL);
        for (int i = 0; i < 4; ++i) QCOMPARE(again.below(1000), draws[std::size_t(i)]);
        std::uint64_t state = 0x5eed5eedULL;
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        QCOMPARE(draws[0], std::size_t((state >> 33) % 1000));
        // The percentile interval of 0..999 at 95 %: the 25th and 974th values.
        std::vector<double> values;
        for (int i = 999; i >= 0; --i) values.push_back(i);
        const Interval i = percentileInterval(values);
        QCOMPARE(i.low, 25.0);
        QCOMPARE(i.high, 974.0);
        std::vector<double> empty;
        QCOMPARE(percentileInterval(empty).low, 0.0);
        QCOMPARE(medianOr({3.0, 1.0, 2.0, 10.0}, -1.0), 2.5);
        QCOMPARE(medianOr({}, -1.0), -1.0);
    }
};

QTEST_GUILESS_MAIN(TestStats)
#include "test_stats.moc"
