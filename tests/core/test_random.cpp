// The simulated rig's random numbers: the block normal generator (RandomStream::normals, the
// ziggurat that every per-sample effect draws from) is a standard normal in distribution - its
// moments, its whole distribution function, both tails and the draws' independence - and repeats
// exactly for a seed.
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/common/Random.h"

using namespace activetouch;

namespace {
constexpr std::size_t kDraws = 2'000'000;

std::vector<double> draws(std::uint64_t seed, std::size_t n = kDraws) {
    RandomStream rng(seed);
    std::vector<double> v(n);
    // In uneven blocks, as effects draw them (a tap at a time, a gap at a time).
    std::size_t at = 0, block = 1;
    while (at < n) {
        const std::size_t take = std::min(block, n - at);
        rng.normals(v.data() + at, take);
        at += take;
        block = block * 3 % 1001 + 1;
    }
    return v;
}

double phi(double x) {
    return 0.5 * std::erfc(-x / std::sqrt(2.0));
}
}  // namespace

class TestRandom : public QObject {
    Q_OBJECT

private slots:
    void momentsAreThoseOfTheStandardNormal() {
        const auto v = draws(7);
        const double n = static_cast<double>(v.size());
        double m1 = 0, m2 = 0, m3 = 0, m4 = 0;
        for (double x : v) {
            m1 += x;
            m2 += x * x;
            m3 += x * x * x;
            m4 += x * x * x * x;
        }
        m1 /= n, m2 /= n, m3 /= n, m4 /= n;
        // Five standard errors of each moment under N(0, 1): 1, sqrt(2), sqrt(15), sqrt(96).
        QVERIFY2(std::abs(m1) < 5 / std::sqrt(n), qPrintable(QString::number(m1)));
        QVERIFY2(std::abs(m2 - 1) < 5 * std::sqrt(2 / n), qPrintable(QString::number(m2)));
        QVERIFY2(std::abs(m3) < 5 * std::sqrt(15 / n), qPrintable(QString::number(m3)));
        QVERIFY2(std::abs(m4 - 3) < 5 * std::sqrt(96 / n), qPrintable(QString::number(m4)));
    }

    void distributionFunctionIsPhi() {
        auto v = draws(11);
        std::sort(v.begin(), v.end());
        const double n = static_cast<double>(v.size());
        double ks = 0;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const double f = phi(v[i]);
            ks = std::max({ks, std::abs(f - i / n), std::abs((i + 1) / n - f)});
        }
        // The Kolmogorov distribution's 0.1 % point is 1.95 / sqrt(n).
        QVERIFY2(ks < 1.95 / std::sqrt(n), qPrintable(QString::number(ks * std::sqrt(n))));
    }

    void tailsBeyondTheBaseLayerHaveTheirShare() {
        // The ziggurat draws values beyond r = 3.44 from a separate tail branch; the wedges
        // between layers from another. Each band's share against Phi, within five binomial SEs.
        const auto v = draws(13, 8'000'000);
        const double n = static_cast<double>(v.size());
        for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
                 {0.0, 0.5}, {1.0, 1.5}, {2.5, 3.0}, {3.0, 3.44}, {3.44, 4.0}, {4.0, 99.0}}) {
            std::size_t count = 0;
            for (double x : v) count += (std::abs(x) >= lo && std::abs(x) < hi) ? 1 : 0;
            const double p = 2 * (phi(hi) - phi(lo));
            const double se = std::sqrt(p * (1 - p) / n);
            QVERIFY2(std::abs(count / n - p) < 5 * se + 1 / n,
                     qPrintable(QString("|z| in [%1, %2): %3 against %4")
                                    .arg(lo)
                                    .arg(hi)
                                    .arg(count / n)
                                    .arg(p)));
        }
    }

    void drawsAreIndependent() {
        const auto v = draws(17);
        const double n = static_cast<double>(v.size() - 1);
        for (std::size_t lag : {1u, 2u, 128u}) {
            double c = 0, signs = 0;
            for (std::size_t i = lag; i < v.size(); ++i) {
                c += v[i] * v[i - lag];
                signs += (v[i] > 0) == (v[i - lag] > 0) ? 1 : -1;
            }
            QVERIFY2(std::abs(c / n) < 5 / std::sqrt(n), qPrintable(QString::number(c / n)));
            QVERIFY(std::abs(signs / n) < 5 / std::sqrt(n));
        }
    }

    void aSeedRepeatsExactly() {
        const auto a = draws(42, 10000), b = draws(42, 10000), c = draws(43, 10000);
        QCOMPARE(a, b);
        QVERIFY(a != c);
        for (double x : a) QVERIFY(std::isfinite(x));
        // An empty block draws nothing and leaves the stream where it was.
        RandomStream r1(5), r2(5);
        double x = 0, y = 0;
        r1.normals(nullptr, 0);
        r1.normals(&x, 1);
        r2.normals(&y, 1);
        QCOMPARE(x, y);
    }
};

QTEST_APPLESS_MAIN(TestRandom)
#include "test_random.moc"
