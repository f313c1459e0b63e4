// Shape recognition from traced paths (paper Figure 9): ideal and perturbed paths, invariance to
// where and how large the path is, and degenerate paths.
#include <QtTest>
#include <cmath>

#include "core/common/Random.h"
#include "core/geometry/ShapeLibrary.h"
#include "core/recognition/PathHistogram.h"

using namespace activetouch;

namespace {
std::vector<ShapeTemplate> libraryTemplates(double sigma) {
    std::vector<ShapeTemplate> t;
    for (const auto& n : libraryShapeNames()) {
        const Polygon p = libraryShape(n, defaultShapeSize(n));
        const PathHistogram raw = idealFollowingHistogram(p, 0.0, 2.0);
        t.push_back({n, raw, smoothed(raw, sigma)});
    }
    return t;
}
double total(const PathHistogram& h) {
    double s = 0;
    for (double v : h.cells) s += v;
    return s;
}
}  // namespace

class TestRecognition : public QObject {
    Q_OBJECT
private slots:
    void idealPathsAreRecognisedFromAnyStart() {
        // A perfect follower starting anywhere along the outline: nearest its own template by
        // both rules, with every template's distance reported.
        const auto templates = libraryTemplates(1.0);
        for (const auto& n : libraryShapeNames()) {
            const Polygon p = libraryShape(n, defaultShapeSize(n));
            for (double startAt : {0.0, 0.3, 0.75, 1.0, 1.6}) {
                const Recognition r =
                    recognise(idealFollowingPath(p, 0.0, 2.0, startAt), templates, 1.0);
                QCOMPARE(r.predicted, n);
                QCOMPARE(r.predictedSmoothed, n);
                QCOMPARE(r.distances.size(), libraryShapeNames().size());
                QCOMPARE(r.smoothedDistances.size(), libraryShapeNames().size());
            }
        }
    }

    void templateIsTheMeanOverStartPoints() {
        // The template does not depend on which vertex the outline lists first: a 47 x 57
        // rectangle listed from its lower left and from its lower right (offset 2 mm outward, the
        // two are 51 mm of ring apart, 25.5 steps) gives the same template, where one fixed start
        // point gives two.
        const std::vector<Vec2> v{{0, 0}, {47, 0}, {47, 57}, {0, 57}};
        const Polygon a(v), b({v[1], v[2], v[3], v[0]});
        const PathHistogram ta = idealFollowingHistogram(a, 2.0, 2.0),
                            tb = idealFollowingHistogram(b, 2.0, 2.0);
        QVERIFY(histogramDistance(ta, tb) < 1e-12);
        QVERIFY(histogramDistance(pathHistogram(idealFollowingPath(a, 2.0, 2.0)),
                                  pathHistogram(idealFollowingPath(b, 2.0, 2.0))) > 0.01);
        QVERIFY(std::abs(total(ta) - 1.0) < 1e-12);
        // One start point is the plain perfect path.
        QCOMPARE(histogramDistance(idealFollowingHistogram(a, 2.0, 2.0, 20, 1),
                                   pathHistogram(idealFollowingPath(a, 2.0, 2.0))),
                 0.0);
    }

    void translationAndScaleDoNotMatter() {
        const Polygon l = libraryShape("L", defaultShapeSize("L"));
        std::vector<Vec2> path = idealFollowingPath(l, 0.0, 2.0), moved;
        for (Vec2 v : path) moved.push_back(1.5 * v + Vec2{300, -40});
        QCOMPARE(histogramDistance(pathHistogram(path), pathHistogram(moved)), 0.0);
    }

    void perturbedPathsStillRecognised() {
        // Taps scattered by 0.5 mm and the path 1 mm inside the outline: the smoothed rule
        // recognises every shape every time; the paper's raw rule is reported beside it.
        const auto templates = libraryTemplates(1.0);
        RandomStream r(5);
        int rawCorrect = 0, smoothCorrect = 0, trials = 0;
        for (int k = 0; k < 10; ++k) {
            for (const auto& n : libraryShapeNames()) {
                const Polygon p = libraryShape(n, defaultShapeSize(n)).transformed(0, {150, 150});
                std::vector<Vec2> path;
                for (Vec2 v : idealFollowingPath(p, -1.0, 2.0))
                    path.push_back(v + Vec2{r.normal(0, 0.5), r.normal(0, 0.5)});
                const Recognition rec = recognise(path, templates, 1.0);
                rawCorrect += rec.predicted == n;
                smoothCorrect += rec.predictedSmoothed == n;
                ++trials;
            }
        }
        QCOMPARE(smoothCorrect, trials);
        QVERIFY(rawCorrect >= trials / 2);
    }

    void degeneratePaths_data() {
        QTest::addColumn<QVector<QPointF>>("points");
        QTest::addColumn<int>("nonZeroCells");
        QTest::newRow("one point") << QVector<QPointF>{{3, 4}} << 1;
        QTest::newRow("all points equal") << QVector<QPointF>(50, QPointF(7, 7)) << 1;
        QTest::newRow("horizontal line") << QVector<QPointF>{{0, 5}, {10, 5}, {20, 5}} << 3;
        QTest::newRow("vertical line") << QVector<QPointF>{{2, 0}, {2, 1}, {2, 2}, {2, 40}} << 3;
        QTest::newRow("diagonal line") << QVector<QPointF>{{0, 0}, {1, 1}, {2, 2}} << 3;
    }
    void degeneratePaths() {
        QFETCH(QVector<QPointF>, points);
        QFETCH(int, nonZeroCells);
        std::vector<Vec2> path;
        for (auto p : points) path.push_back({p.x(), p.y()});
        const PathHistogram h = pathHistogram(path);
        int nonZero = 0;
        for (double v : h.cells) {
            QVERIFY(std::isfinite(v));
            nonZero += v > 0;
        }
        QCOMPARE(nonZero, nonZeroCells);
        QVERIFY(std::abs(total(h) - 1.0) < 1e-12);
        const PathHistogram s = smoothed(h, 1.0);
        QVERIFY(std::abs(total(s) - 1.0) < 1e-12);
        const Recognition r = recognise(path, libraryTemplates(1.0), 1.0);
        for (const auto& [shape, d] : r.distances) QVERIFY(std::isfinite(d));
        QVERIFY(!r.predicted.empty());
    }

    void emptyPath() {
        const PathHistogram h = pathHistogram({});
        QCOMPARE(total(h), 0.0);
        QCOMPARE(total(smoothed(h, 1.0)), 0.0);
        const Recognition r = recognise({}, libraryTemplates(1.0), 1.0);
        for (const auto& [shape, d] : r.distances) QVERIFY(std::isfinite(d));
    }

    void idealPathSpacing() {
        const Polygon sq({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
        const auto path = idealFollowingPath(sq, 1.0, 2.0);  // a 12 x 12 ring: 48 mm
        QCOMPARE(int(path.size()), 24);
        QCOMPARE(path.front().x, -1.0);
        QCOMPARE(path.front().y, -1.0);
        const auto later = idealFollowingPath(sq, 1.0, 2.0, 0.5);  // starts half a millimetre on
        QCOMPARE(int(later.size()), 24);
        QCOMPARE(later.front().x, -0.5);
        QCOMPARE(later.front().y, -1.0);
    }
};

QTEST_APPLESS_MAIN(TestRecognition)
#include "test_recognition.moc"
