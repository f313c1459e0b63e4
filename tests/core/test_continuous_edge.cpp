// The continuous edge percept (core/classify/ContinuousEdge.h) on synthetic log-likelihoods: the
// angle follows the posterior between classes and across the wrap at 0/360 degrees, and flat,
// one-hot, ruled-out and hostile inputs give a clear answer, never a NaN.
#include <QtTest>
#include <cmath>
#include <limits>
#include <vector>

#include "core/classify/ContinuousEdge.h"

using namespace activetouch;

namespace {
/// `orientations` evenly round the circle from 0 degrees, `positions` positions, every class an
/// edge class unless `regions` says otherwise.
ClassSet evenClasses(int orientations, int positions) {
    ClassSet cs;
    cs.orientationsDeg.clear();
    for (int o = 0; o < orientations; ++o) cs.orientationsDeg.push_back(360.0 * o / orientations);
    cs.positions = positions;
    return cs;
}

constexpr double kRuledOut = -std::numeric_limits<double>::infinity();

/// Log-likelihoods that put probability `p[i]` on class `classes[i]` and none elsewhere.
std::vector<double> logsOf(const ClassSet& cs, const std::vector<std::pair<int, double>>& mass) {
    std::vector<double> logs(std::size_t(cs.classCount()), kRuledOut);
    for (const auto& [cls, p] : mass) logs[std::size_t(cls)] = std::log(p);
    return logs;
}

bool finite(const ContinuousEdge& e) {
    return std::isfinite(e.angleDeg) && std::isfinite(e.concentration) &&
           std::isfinite(e.position) && std::isfinite(e.edgeWeight);
}
}  // namespace

class TestContinuousEdge : public QObject {
    Q_OBJECT
private slots:
    void aOneHotPosteriorGivesItsClassExactly() {
        const ClassSet cs = evenClasses(36, 18);
        for (int o : {0, 1, 9, 17, 35})
            for (int p : {1, 7, 18}) {
                const auto logs = logsOf(cs, {{cs.classOf(o, p), 1.0}});
                const ContinuousEdge e = continuousEdge(cs, logs.data());
                QVERIFY(e.angleValid && e.positionValid);
                QVERIFY(std::abs(e.angleDeg - 10.0 * o) < 1e-9);
                QCOMPARE(e.position, double(p));
                QVERIFY(std::abs(e.concentration - 1.0) < 1e-12);
                QCOMPARE(e.edgeWeight, 1.0);
            }
    }

    void theAngleFallsBetweenClassesAsThePosteriorDoes() {
        const ClassSet cs = evenClasses(36, 18);
        // 30 % at 40 degrees, 70 % at 50: the weighted circular mean lies between, nearer 50.
        const auto logs = logsOf(cs, {{cs.classOf(4, 9), 0.3}, {cs.classOf(5, 10), 0.7}});
        const ContinuousEdge e = continuousEdge(cs, logs.data());
        QVERIFY(e.angleValid);
        const double expected =
            std::atan2(0.3 * std::sin(40 * M_PI / 180) + 0.7 * std::sin(50 * M_PI / 180),
                       0.3 * std::cos(40 * M_PI / 180) + 0.7 * std::cos(50 * M_PI / 180)) *
            180 / M_PI;
        // The weights are single-precision exponentials (to about 2e-7 of each): the mean to
        // within a millionth of a degree and of a position.
        QVERIFY2(std::abs(e.angleDeg - expected) < 1e-5,
                 qPrintable(QString::number(e.angleDeg - expected)));
        QVERIFY(e.angleDeg > 45.0 && e.angleDeg < 50.0);
        QVERIFY(std::abs(e.position - 9.7) < 1e-6);
        QVERIFY(e.concentration < 1.0 && e.concentration > 0.99);
    }

    void theAngleWrapsRoundZero() {
        // Equal weight at 350 and 10 degrees: 0, not 180 (an arithmetic mean would say 180).
        const ClassSet cs = evenClasses(36, 18);
        const auto logs = logsOf(cs, {{cs.classOf(35, 9), 0.5}, {cs.classOf(1, 9), 0.5}});
        const ContinuousEdge e = continuousEdge(cs, logs.data());
        QVERIFY(e.angleValid);
        QVERIFY2(std::min(e.angleDeg, 360.0 - e.angleDeg) < 1e-9,
                 qPrintable(QString::number(e.angleDeg)));
        QVERIFY(e.angleDeg >= 0.0 && e.angleDeg < 360.0);
        // More weight at 350: just below 360, still in [0, 360).
        const auto leaning = logsOf(cs, {{cs.classOf(35, 9), 0.6}, {cs.classOf(1, 9), 0.4}});
        const ContinuousEdge l = continuousEdge(cs, leaning.data());
        QVERIFY(l.angleDeg > 355.0 && l.angleDeg < 360.0);
        // Across +-180 degrees: equal weight at 170 and 190 (-170) gives 180, not 0.
        const auto back = logsOf(cs, {{cs.classOf(17, 9), 0.5}, {cs.classOf(19, 9), 0.5}});
        const ContinuousEdge b = continuousEdge(cs, back.data());
        QVERIFY(b.angleValid);
        QVERIFY2(std::abs(b.angleDeg - 180.0) < 1e-9, qPrintable(QString::number(b.angleDeg)));
        // The paper's four orientations (270, 0, 90, 180) wrap the same way.
        ClassSet paper;
        const auto between =
            logsOf(paper, {{paper.classOf(0, 9), 0.5}, {paper.classOf(1, 9), 0.5}});
        const ContinuousEdge p = continuousEdge(paper, between.data());
        QVERIFY(p.angleValid);
        QVERIFY(std::abs(p.angleDeg - 315.0) < 1e-9);
    }

    void aFlatPosteriorHasNoMeanAngleButNoNaN() {
        // Every class equally likely: the normals cancel, so there is no angle; the position is
        // the middle of the grid.
        for (int orientations : {4, 8, 36}) {
            const ClassSet cs = evenClasses(orientations, 18);
            const std::vector<double> logs(std::size_t(cs.classCount()), -1234.5);
            const ContinuousEdge e = continuousEdge(cs, logs.data());
            QVERIFY(finite(e));
            QVERIFY(!e.angleValid);
            QVERIFY(e.concentration < 1e-9);
            QVERIFY(e.positionValid);
            QVERIFY(std::abs(e.position - 9.5) < 1e-9);
            QVERIFY(std::abs(e.edgeWeight - 1.0) < 1e-12);
        }
        // Two opposite orientations equally likely cancel too.
        const ClassSet cs = evenClasses(4, 18);
        const auto opposite = logsOf(cs, {{cs.classOf(0, 5), 0.5}, {cs.classOf(2, 5), 0.5}});
        const ContinuousEdge e = continuousEdge(cs, opposite.data());
        QVERIFY(!e.angleValid && e.positionValid && finite(e));
    }

    void planeAndAirCarryNoOrientation() {
        ClassSet cs = evenClasses(4, 18);
        cs.regions.assign(std::size_t(cs.classCount()), Region::Edge);
        for (int o = 0; o < 4; ++o) {
            cs.regions[std::size_t(cs.classOf(o, 1))] = Region::Plane;
            cs.regions[std::size_t(cs.classOf(o, 18))] = Region::Air;
        }
        // All the weight on plane and air: no edge percept at all.
        const auto flat = logsOf(cs, {{cs.classOf(0, 1), 0.5}, {cs.classOf(2, 18), 0.5}});
        const ContinuousEdge none = continuousEdge(cs, flat.data());
        QVERIFY(!none.angleValid && !none.positionValid && finite(none));
        QCOMPARE(none.edgeWeight, 0.0);
        // Some on an edge: the angle is that edge's, the weight says how much.
        const auto some = logsOf(cs, {{cs.classOf(0, 1), 0.75}, {cs.classOf(1, 8), 0.25}});
        const ContinuousEdge e = continuousEdge(cs, some.data());
        QVERIFY(e.angleValid);
        QVERIFY(std::abs(e.angleDeg - 90.0) < 1e-9);
        QVERIFY(std::abs(e.edgeWeight - 0.25) < 1e-6);
        QCOMPARE(e.position, 8.0);
    }

    void hugeAndHostileValuesGiveAClearAnswer() {
        const ClassSet cs = evenClasses(8, 18);
        std::vector<double> logs(std::size_t(cs.classCount()), -1e300);
        logs[std::size_t(cs.classOf(2, 4))] = -1e299;  // sums of log-probabilities can be vast
        const ContinuousEdge big = continuousEdge(cs, logs.data());
        QVERIFY(big.angleValid && finite(big));
        QVERIFY(std::abs(big.angleDeg - 90.0) < 1e-9);
        // Every class ruled out, a NaN, +infinity, a bad temperature, no classes: nothing valid.
        const std::vector<double> out(std::size_t(cs.classCount()), kRuledOut);
        std::vector<double> nan = logs, inf = logs;
        nan[3] = std::nan("");
        inf[5] = std::numeric_limits<double>::infinity();
        for (const ContinuousEdge& e :
             {continuousEdge(cs, out.data()), continuousEdge(cs, nan.data()),
              continuousEdge(cs, inf.data()), continuousEdge(cs, logs.data(), 0.0),
              continuousEdge(cs, logs.data(), -1.0), continuousEdge(cs, logs.data(), std::nan("")),
              continuousEdge(cs, nullptr)}) {
            QVERIFY(!e.angleValid && !e.positionValid);
            QVERIFY(finite(e));
        }
        ClassSet empty;
        empty.orientationsDeg.clear();
        QVERIFY(!continuousEdge(empty, logs.data()).angleValid);
    }

    void aHigherTemperatureSpreadsTheBelief() {
        const ClassSet cs = evenClasses(36, 18);
        std::vector<double> logs(std::size_t(cs.classCount()), -600.0);
        logs[std::size_t(cs.classOf(3, 9))] = -500.0;
        logs[std::size_t(cs.classOf(4, 9))] = -520.0;
        const ContinuousEdge sharp = continuousEdge(cs, logs.data());
        const ContinuousEdge soft = continuousEdge(cs, logs.data(), 50.0);
        QVERIFY(sharp.angleValid && soft.angleValid);
        QVERIFY(std::abs(sharp.angleDeg - 30.0) < 1e-6);        // 100 nats apart: one class
        QVERIFY(soft.angleDeg > 30.0 && soft.angleDeg < 40.0);  // tempered: between
        QVERIFY(soft.concentration < sharp.concentration);
    }
};

QTEST_APPLESS_MAIN(TestContinuousEdge)
#include "test_continuous_edge.moc"
