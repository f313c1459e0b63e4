// The simulated rig's random numbers: the block normal generator (RandomStream::normals, which
// every per-sample effect draws from) gives exactly what normal() gives, call for call; both are a
// standard normal in distribution - their moments, their whole distribution function, both tails
// and the draws' independence - and repeat exactly for a seed. The polar method's logarithm is the
// generator's own, within two units in the last place everywhere.
#include <QtTest>
#include <algorithm>
#include <bit>
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

    void tailsHaveTheirShare() {
        // The far tails come from the smallest radii of the polar method (|z| > 4 needs s below
        // about 3e-4), where the logarithm is steepest. Each band's share against Phi, within five
        // binomial SEs.
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

    void blocksGiveExactlyWhatNormalGives() {
        // Blocks of every length from 0 to 700 (odd ones leave a spare), single normal() calls in
        // between: the same values bit for bit, and the stream where normal()'s calls leave it.
        RandomStream blocks(99), single(99), lengths(3);
        std::size_t values = 0;
        for (int round = 0; round < 3000; ++round) {
            const std::size_t n = lengths.next() % 701;
            std::vector<double> got(n), want(n);
            blocks.normals(got.data(), n);
            for (double& x : want) x = single.normal();
            QVERIFY2(std::equal(got.begin(), got.end(), want.begin(),
                                [](double a, double b) {
                                    return std::bit_cast<std::uint64_t>(a) ==
                                           std::bit_cast<std::uint64_t>(b);
                                }),
                     qPrintable(QString("a block of %1 in round %2").arg(n).arg(round)));
            values += n;
            if (round % 7 == 0) QCOMPARE(blocks.normal(), single.normal());
            QCOMPARE(blocks.uniform(), single.uniform());
        }
        QVERIFY(values > 900'000);
    }

    void theLogarithmIsWithinTwoUnitsInTheLastPlace() {
        // Against the long double logarithm, over the unit disc's radii the polar method takes
        // (down to 2^-104), values next to 1 on either side, powers of two and every binade.
        auto ulpsOff = [](double x) {
            const long double want = std::log(static_cast<long double>(x));
            const double got = RandomStream::logOfPositive(x);
            if (want == 0.0L) return got == 0.0 ? 0.0 : HUGE_VAL;
            const double w = static_cast<double>(want);
            const double ulp = std::nextafter(std::abs(w), HUGE_VAL) - std::abs(w);
            return static_cast<double>(std::abs(static_cast<long double>(got) - want) / ulp);
        };
        RandomStream rng(21);
        double worst = 0.0, at = 0.0;
        auto check = [&](double x) {
            const double off = ulpsOff(x);
            if (off > worst) worst = off, at = x;
        };
        for (int i = 0; i < 400'000; ++i) {
            const double u = 2 * rng.uniform() - 1, v = 2 * rng.uniform() - 1;
            if (u * u + v * v < 1.0 && u * u + v * v > 0.0) check(u * u + v * v);
            check(std::nextafter(1.0, 0.0) - (i % 1000) * 0x1p-53);
            check(1.0 + (i % 1000) * 0x1p-52);
            check(std::ldexp(0.5 + 0.5 * rng.uniform(), static_cast<int>(i % 2000) - 1000));
        }
        for (int k = -1022; k <= 1023; ++k) check(std::ldexp(1.0, k));
        for (double x : {0x1p-104, 0.5, 0.7071067811865476, 1.4142135623730951, 2.0, 1e300})
            check(x);
        QVERIFY2(worst <= 2.0, qPrintable(QString("%1 units at %2").arg(worst).arg(at, 0, 'a')));
        QCOMPARE(RandomStream::logOfPositive(1.0), 0.0);
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
