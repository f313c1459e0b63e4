// Sequential Bayesian perception stays numerically stable: identical evidence a thousand times,
// contradictory evidence, a class ruled out, thresholds of 0.5 and 0.999999; posteriors always sum
// to one within 1e-12 and never hold NaN.
#include <QtTest>
#include <cmath>
#include <limits>

#include "core/classify/SequentialPerception.h"
#include "core/common/Random.h"

using namespace activetouch;

namespace {
void verifyNormalised(const SequentialBelief& b) {
    long double total = 0;
    for (double v : b.logPosterior()) {
        QVERIFY(!std::isnan(v));
        total += std::exp(static_cast<long double>(v));
    }
    QVERIFY2(std::abs(static_cast<double>(total) - 1.0) <= 1e-12,
             qPrintable(QString::number(static_cast<double>(total), 'g', 17)));
}
}  // namespace

class TestSequentialPerception : public QObject {
    Q_OBJECT
    ClassSet classes_;

private slots:
    void thousandTapsOfIdenticalEvidence() {
        SequentialBelief b(classes_);
        std::vector<double> ll(72, -3000.0);
        ll[17] = -2990.0;  // class 17 a little more likely each time
        for (int i = 0; i < 1000; ++i) {
            b.update(ll.data());
            verifyNormalised(b);
        }
        QCOMPARE(b.best(), 17);
        QCOMPARE(b.bestPosterior(), 1.0);
        QCOMPARE(b.taps(), 1000);
        for (int c = 0; c < 72; ++c)
            if (c != 17) QVERIFY(b.posterior(c) >= 0.0 && b.posterior(c) < 1e-300);
    }

    void contradictoryEvidence() {
        SequentialBelief b(classes_);
        std::vector<double> a(72, -500.0), z(72, -500.0);
        a[3] = -400.0;
        z[40] = -400.0;
        for (int i = 0; i < 500; ++i) {
            b.update(a.data());
            b.update(z.data());
            verifyNormalised(b);
        }
        // Equal evidence both ways: a tie between the two, broken to the lower class.
        QVERIFY(std::abs(b.posterior(3) - 0.5) < 1e-9);
        QVERIFY(std::abs(b.posterior(40) - 0.5) < 1e-9);
        QCOMPARE(b.best(), 3);
        QVERIFY(b.bestPosterior() > 0.5 - 1e-9);  // at the 0.5 threshold only up to rounding
        QVERIFY(!b.decided(0.999999));
    }

    void aClassWithZeroLikelihood() {
        SequentialBelief b(classes_);
        std::vector<double> ll(72, -10.0);
        ll[5] = -std::numeric_limits<double>::infinity();
        b.update(ll.data());
        verifyNormalised(b);
        QCOMPARE(b.posterior(5), 0.0);
        // Ruled out for good, whatever comes next.
        std::vector<double> favour(72, -10.0);
        favour[5] = 0.0;
        for (int i = 0; i < 10; ++i) b.update(favour.data());
        QCOMPARE(b.posterior(5), 0.0);
        verifyNormalised(b);
        // Every class ruled out: no NaN, a flat belief.
        std::vector<double> none(72, -std::numeric_limits<double>::infinity());
        b.update(none.data());
        verifyNormalised(b);
        QVERIFY(std::abs(b.bestPosterior() - 1.0 / 72) < 1e-12);
        // NaN evidence counts as ruling the class out, never as NaN belief.
        SequentialBelief c(classes_);
        std::vector<double> withNan(72, -1.0);
        withNan[9] = std::numeric_limits<double>::quiet_NaN();
        c.update(withNan.data());
        verifyNormalised(c);
        QCOMPARE(c.posterior(9), 0.0);
    }

    void thresholds_data() {
        QTest::addColumn<double>("threshold");
        QTest::addColumn<int>("tapsNeeded");
        // Each tap favours class 11 by a factor e over each of the others: after n taps its
        // posterior is e^n / (e^n + 71).
        QTest::newRow("0.5") << 0.5 << 5;
        QTest::newRow("0.999999") << 0.999999 << 19;
    }
    void thresholds() {
        QFETCH(double, threshold);
        QFETCH(int, tapsNeeded);
        SequentialBelief b(classes_);
        std::vector<double> ll(72, -1.0);
        ll[11] = 0.0;
        while (!b.decided(threshold)) {
            b.update(ll.data());
            verifyNormalised(b);
            QVERIFY(b.taps() <= 100);
        }
        QCOMPARE(b.taps(), tapsNeeded);
        QCOMPARE(b.best(), 11);
    }

    void randomEvidenceStaysNormalised() {
        RandomStream r(3);
        SequentialBelief b(classes_);
        std::vector<double> ll(72);
        for (int i = 0; i < 2000; ++i) {
            for (double& v : ll) v = r.normal(-600, 200);
            b.update(ll.data());
            if (i % 7 == 0) b.shift({r.uniform(-2, 2), r.uniform(-2, 2)});
            verifyNormalised(b);
        }
    }

    void shiftFollowsTheTip() {
        // All belief on "lower edge, position 9"; the tip moves 2 mm down (outward for the lower
        // edge): the belief moves to position 11.
        SequentialBelief b(classes_);
        std::vector<double> ll(72, -1000.0);
        ll[classes_.classOf(0, 9)] = 0.0;
        b.update(ll.data());
        b.shift({0.0, -2.0});
        QCOMPARE(b.best(), classes_.classOf(0, 11));
        verifyNormalised(b);
        b.shift({0.0, -50.0});  // far past the window: the mass stays at the end
        QCOMPARE(b.best(), classes_.classOf(0, 18));
        verifyNormalised(b);
    }
};

QTEST_APPLESS_MAIN(TestSequentialPerception)
#include "test_sequential_perception.moc"
