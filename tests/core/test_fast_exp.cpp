// The exponential behind every posterior (core/common/FastExp.h): within 2 ulp of std::exp over
// its whole domain, exact at its ends, clamped outside it, and a log-sum-exp built on it that
// still handles the degenerate inputs a classifier hands it (ruled-out classes, one class, NaN).
#include <QtTest>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/classify/HistogramClassifier.h"
#include "core/common/FastExp.h"

using namespace activetouch;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

double ulpsApart(double a, double b) {
    return std::abs(a - b) / (std::nextafter(b, kInf) - b);
}
}  // namespace

class TestFastExp : public QObject {
    Q_OBJECT

private slots:
    void withinTwoUlpOverTheDomain() {
        std::mt19937_64 g(3);
        std::uniform_real_distribution<double> wide(kExpFloor, 0.0), near(-3.0, 0.0);
        double worst = 0.0, worstAt = 0.0;
        for (int i = 0; i < 2'000'000; ++i) {
            const double x = i % 2 ? wide(g) : near(g);
            const double u = ulpsApart(expNonPositive(x), std::exp(x));
            if (u > worst) worst = u, worstAt = x;
        }
        // Each boundary of the range reduction (x a multiple of ln 2 / 2) and the two ends.
        for (int k = 0; k <= 2042; ++k) {
            const double x = -k * 0.5 * std::log(2.0);
            if (x < kExpFloor) break;
            for (double d : {-1e-12, 0.0, 1e-12})
                if (x + d <= 0.0 && x + d >= kExpFloor)
                    worst = std::max(worst, ulpsApart(expNonPositive(x + d), std::exp(x + d)));
        }
        QVERIFY2(worst <= 2.0,
                 qPrintable(QString("%1 ulp at %2").arg(worst).arg(worstAt, 0, 'g', 17)));
        QCOMPARE(expNonPositive(0.0), 1.0);
        QCOMPARE(expNonPositive(-0.0), 1.0);
        QVERIFY(ulpsApart(expNonPositive(kExpFloor), std::exp(kExpFloor)) <= 2.0);
    }

    void clampedOutsideTheDomain() {
        QCOMPARE(expNonPositive(1.0), 1.0);
        QCOMPARE(expNonPositive(kInf), 1.0);
        QCOMPARE(expNonPositive(-1000.0), expNonPositive(kExpFloor));
        QCOMPARE(expNonPositive(-kInf), expNonPositive(kExpFloor));
        QCOMPARE(expNonPositive(std::numeric_limits<double>::quiet_NaN()),
                 expNonPositive(kExpFloor));
    }

    void logSumExpStaysExactEnough() {
        // Against the sum in long double, for spreads from a few nats to thousands.
        std::mt19937_64 g(5);
        for (double spread : {1.0, 30.0, 800.0, 5000.0}) {
            std::uniform_real_distribution<double> d(-spread, 0.0);
            for (int n : {1, 3, 4, 7, 72, 648}) {
                std::vector<double> v(static_cast<std::size_t>(n));
                for (double& x : v) x = d(g) - 1234.5;
                long double top = -kInf, sum = 0;
                for (double x : v) top = std::max<long double>(top, x);
                for (double x : v) sum += std::exp(static_cast<long double>(x) - top);
                const double want = static_cast<double>(top + std::log(sum));
                QVERIFY2(std::abs(logSumExp(v.data(), n) - want) <= 1e-12 * std::abs(want),
                         qPrintable(QString("n %1 spread %2").arg(n).arg(spread)));
            }
        }
        // Ruled-out classes add nothing; all ruled out is -infinity; +infinity wins; NaN is left
        // out; no classes at all is -infinity.
        const std::vector<double> some{-kInf, -2.0, -kInf, -2.0, -kInf};
        QCOMPARE(logSumExp(some.data(), 5), -2.0 + std::log(2.0));
        const std::vector<double> none(5, -kInf);
        QCOMPARE(logSumExp(none.data(), 5), -kInf);
        const std::vector<double> inf{-1.0, kInf};
        QCOMPARE(logSumExp(inf.data(), 2), kInf);
        const std::vector<double> nan{std::numeric_limits<double>::quiet_NaN(), -3.0, -3.0};
        QCOMPARE(logSumExp(nan.data(), 3), -3.0 + std::log(2.0));
        QCOMPARE(logSumExp(nullptr, 0), -kInf);
    }
};

QTEST_APPLESS_MAIN(TestFastExp)
#include "test_fast_exp.moc"
