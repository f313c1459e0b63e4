// Sequential Bayesian perception stays numerically stable: identical evidence a thousand times,
// contradictory evidence, a class ruled out, thresholds of 0.5 and 0.999999; posteriors always sum
// to one within 1e-12 and never hold NaN.
#include <QtTest>
#include <cmath>
#include <limits>

#include "core/classify/BeliefCalibration.h"
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

    void expectedCalibrationErrorByHand() {
        // Four taps at 0.9 of which three are right, two at 0.3 of which one is: |0.75 - 0.9|
        // over four taps and |0.5 - 0.3| over two.
        std::vector<ReliabilityBin> bins;
        const double ece = expectedCalibrationError(
            {0.9, 0.9, 0.9, 0.9, 0.3, 0.3}, {true, true, true, false, false, true}, 10, &bins);
        QVERIFY(std::abs(ece - (4 * 0.15 + 2 * 0.2) / 6) < 1e-12);
        QCOMPARE(bins.size(), std::size_t{10});
        QCOMPARE(bins[9].taps, 4);
        QCOMPARE(bins[3].taps, 2);
        QCOMPARE(bins[9].accuracy, 0.75);
        // A confidence of exactly 1 falls in the top bin; none at all gives 0, not NaN.
        QCOMPARE(expectedCalibrationError({1.0, 1.0}, {true, true}, 10), 0.0);
        QCOMPARE(expectedCalibrationError({}, {}, 10), 0.0);
        QCOMPARE(expectedCalibrationError({qQNaN()}, {false}, 10), 0.0);  // NaN counts as 0
    }

    void scaledBeliefsStayFiniteAndKeepTheArgmax() {
        // Scaling never moves the winner, at any factor a calibration can give; and at extreme
        // factors and likelihoods the posterior stays a number in [0, 1].
        RandomStream r(61);
        std::vector<double> ll(72);
        for (int trial = 0; trial < 200; ++trial) {
            for (double& v : ll) v = -3000.0 + 400.0 * r.uniform();
            int top = -1;
            const int exact = argmaxLowestIndex(ll.data(), 72);
            for (double scale : {1.0, 0.0159, 1.0 / 600, 1e-6}) {
                const double p = scaledTopPosterior(ll.data(), 72, scale, &top);
                QCOMPARE(top, exact);
                QVERIFY(p > 0.0 && p <= 1.0);
            }
        }
        const double inf = std::numeric_limits<double>::infinity();
        const std::vector<std::vector<double>> hostile{
            {-inf, -inf, -inf}, {qQNaN(), qQNaN(), qQNaN()}, {-1e308, -1e308, 0.0},
            {inf, 0.0, -inf},   {-1e308, 1e308, qQNaN()},    {0.0, 0.0, 0.0}};
        for (const auto& h : hostile)
            for (double scale : {0.0, 1e-300, 1e-3, 1.0, 1e300, inf, qQNaN(), -1.0}) {
                int top = -1;
                const double p = scaledTopPosterior(h.data(), 3, scale, &top);
                QVERIFY2(std::isfinite(p) && p >= 0.0 && p <= 1.0 && top >= 0 && top < 3,
                         qPrintable(QString("scale %1 gives %2").arg(scale).arg(p)));
            }
        // Fitting a factor on taps that are right with 80 % confidence at factor 0.01.
        std::vector<std::vector<double>> taps;
        std::vector<int> truth;
        for (int t = 0; t < 400; ++t) {
            std::vector<double> v(4, -100.0 * std::log(20.0));  // each wrong class: 1/20 as likely
            v[0] = 0.0;
            taps.push_back(v);
            truth.push_back(r.uniform() < 0.87 ? 0 : 1 + t % 3);
        }
        const double s = fitLogLikelihoodScale(taps, truth);
        // With a floor too: the same confidence on these taps, and a floor fitted where a fifth
        // of the "certain" taps are wrong whatever the scale.
        const BeliefScaling plain = fitBeliefScaling(taps, truth);
        QVERIFY(std::abs(calibratedTopBelief(taps[0].data(), 4, plain, nullptr) - 0.87) < 0.05);
        std::vector<std::vector<double>> sure;
        std::vector<int> sureTruth;
        for (int t = 0; t < 500; ++t) {
            std::vector<double> v(4, -1e5);
            v[0] = 0.0;
            sure.push_back(v);
            sureTruth.push_back(t % 5 == 0 ? 1 + t % 3 : 0);
        }
        const BeliefScaling floored = fitBeliefScaling(sure, sureTruth);
        qInfo("floor %.3f scale %.3g for 80 %% right at any scale", floored.floor, floored.scale);
        int sureTop = -1;
        QVERIFY(std::abs(calibratedTopBelief(sure[0].data(), 4, floored, &sureTop) - 0.8) < 0.02);
        QCOMPARE(sureTop, 0);
        int top = 0;
        qInfo("fitted factor %.5f; confidence %.3f for 87 %% right", s,
              scaledTopPosterior(taps[0].data(), 4, s, &top));
        QVERIFY(std::abs(scaledTopPosterior(taps[0].data(), 4, s, &top) - 0.87) < 0.05);
    }

    void calibratedBeliefStaysFiniteAndKeepsTheArgmax() {
        // Every scale and floor a calibration can give, and hostile ones, on extreme evidence:
        // the log belief is finite or -inf, normalised, and its top is the evidence's argmax.
        RandomStream r(67);
        const double inf = std::numeric_limits<double>::infinity();
        std::vector<double> ll(72), out(72);
        for (int trial = 0; trial < 100; ++trial) {
            for (double& v : ll) v = -1e6 * r.uniform();
            const int exact = argmaxLowestIndex(ll.data(), 72);
            for (const BeliefScaling sc :
                 {BeliefScaling{1.0, 0.0}, BeliefScaling{0.016, 0.0}, BeliefScaling{0.009, 0.2},
                  BeliefScaling{1e-8, 0.99}, BeliefScaling{1e-300, 0.5},
                  BeliefScaling{1.0, 1e-300}}) {
                calibratedLogBelief(ll.data(), 72, sc, out.data());
                long double total = 0;
                for (double v : out) {
                    QVERIFY(!std::isnan(v) && v <= 1e-12);
                    total += std::exp(static_cast<long double>(v));
                }
                QVERIFY(std::abs(static_cast<double>(total) - 1.0) < 1e-9);
                QCOMPARE(argmaxLowestIndex(out.data(), 72) == exact ||
                             out[static_cast<std::size_t>(argmaxLowestIndex(out.data(), 72))] ==
                                 out[static_cast<std::size_t>(exact)],
                         true);
                int top = -1;
                const double p = calibratedTopBelief(ll.data(), 72, sc, &top);
                QCOMPARE(top, exact);
                QVERIFY(p > 0.0 && p <= 1.0);
                // A sequential belief fed it a thousand times stays normalised.
                SequentialBelief b(classes_);
                for (int k = 0; k < 1000; ++k) b.update(out.data());
                verifyNormalised(b);
            }
        }
        const std::vector<std::vector<double>> hostile{
            {-inf, -inf, -inf}, {qQNaN(), qQNaN(), qQNaN()}, {-1e308, -1e308, 0.0},
            {inf, 0.0, -inf},   {-1e308, 1e308, qQNaN()},    {0.0, 0.0, 0.0}};
        for (const auto& h : hostile)
            for (double scale : {0.0, 1e-300, 1e-3, 1.0, 1e300, inf, qQNaN(), -1.0})
                for (double floor : {0.0, 0.5, 1.0, 2.0, -1.0, qQNaN(), inf}) {
                    std::vector<double> o(3);
                    calibratedLogBelief(h.data(), 3, {scale, floor}, o.data());
                    long double total = 0;
                    for (double v : o) {
                        QVERIFY2(!std::isnan(v) && v != inf,
                                 qPrintable(QString("scale %1 floor %2").arg(scale).arg(floor)));
                        total += std::exp(static_cast<long double>(v));
                    }
                    QVERIFY(std::abs(static_cast<double>(total) - 1.0) < 1e-9);
                }
        // A floor keeps a class the tap all but rules out believable.
        std::vector<double> two{0.0, -1e9};
        std::vector<double> o(2);
        calibratedLogBelief(two.data(), 2, {1.0, 0.2}, o.data());
        QVERIFY(std::abs(std::exp(o[1]) - 0.1) < 1e-12);
    }

    void planeAndAirAreDecidedAsOnePerceptEach() {
        // Two orientations x 3 positions: position 1 plane, 2 edge, 3 air.
        ClassSet cs;
        cs.orientationsDeg = {270, 0};
        cs.positions = 3;
        cs.regions = {Region::Plane, Region::Edge, Region::Air,
                      Region::Plane, Region::Edge, Region::Air};
        SequentialBelief b(cs);
        // Plane most likely, spread evenly over both orientations (0.33 + 0.3); an edge at 0.31.
        std::vector<double> ll{std::log(0.33), std::log(0.31), std::log(0.02),
                               std::log(0.3),  std::log(0.02), std::log(0.02)};
        b.update(ll.data());
        QCOMPARE(b.best(), 0);
        QVERIFY(std::abs(b.perceptBelief() - 0.63) < 1e-12);  // the plane's whole mass
        QVERIFY(b.decided(0.63 - 1e-9) && !b.decided(0.64));
        // An edge class most likely: its own posterior only.
        SequentialBelief e(cs);
        std::vector<double> le{std::log(0.2), std::log(0.4),  std::log(0.1),
                               std::log(0.2), std::log(0.05), std::log(0.05)};
        e.update(le.data());
        QCOMPARE(e.best(), 1);
        QVERIFY(std::abs(e.perceptBelief() - 0.4) < 1e-12);
        // Without regions, every class is its own percept: the largest posterior.
        SequentialBelief flat(classes_);
        std::vector<double> l72(72, -10.0);
        l72[5] = 0.0;
        flat.update(l72.data());
        QCOMPARE(flat.best(), 5);
        QCOMPARE(flat.perceptBelief(), flat.bestPosterior());
    }
};

QTEST_APPLESS_MAIN(TestSequentialPerception)
#include "test_sequential_perception.moc"
