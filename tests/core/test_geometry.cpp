// Object outlines: the library shapes, containment and distances the physics relies on, and the
// outlines a scene must refuse.
#include <QtTest>

#include "core/geometry/Polygon.h"
#include "core/geometry/ShapeLibrary.h"

using namespace activetouch;

class TestGeometry : public QObject {
    Q_OBJECT
private slots:
    void libraryShapeAreas_data() {
        QTest::addColumn<QString>("shape");
        QTest::addColumn<double>("area");
        QTest::addColumn<int>("vertices");
        QTest::newRow("rectangle 48 x 58") << "rectangle" << 48.0 * 58.0 << 4;
        QTest::newRow("cross 60, arm 20") << "cross" << 3600.0 - 4 * 400.0 << 12;
        QTest::newRow("C 60, arm 20, opening 20") << "C" << 3600.0 - 40.0 * 20.0 << 8;
        QTest::newRow("L 60, arm 20") << "L" << 3600.0 - 40.0 * 40.0 << 6;
    }
    void libraryShapeAreas() {
        QFETCH(QString, shape);
        QFETCH(double, area);
        QFETCH(int, vertices);
        const Polygon p = libraryShape(shape.toStdString(), defaultShapeSize(shape.toStdString()));
        QCOMPARE(p.area(), area);
        QCOMPARE(int(p.size()), vertices);
        // Centred on the bounding box.
        QCOMPARE(p.boundingBoxMin().x + p.boundingBoxMax().x, 0.0);
        QCOMPARE(p.boundingBoxMin().y + p.boundingBoxMax().y, 0.0);
    }

    void containmentAndSignedDistance() {
        const Polygon l =
            libraryShape("L", defaultShapeSize("L"));  // x, y in -30..30, notch top right
        QVERIFY(l.contains({-25, 25}));
        QVERIFY(l.contains({25, -25}));
        QVERIFY(!l.contains({10, 10}));              // inside the notch
        QCOMPARE(l.signedDistance({-20, 0}), 10.0);  // mid-arm: 10 mm from both sides
        QCOMPARE(l.signedDistance({-35, 0}), -5.0);
        QCOMPARE(l.signedDistance({0, 0}), -10.0);  // in the notch, 10 mm from both inner edges
    }

    void windingIsNormalisedCounterClockwise() {
        const Polygon cw({{0, 0}, {0, 10}, {10, 10}, {10, 0}});
        // The first edge's outward normal must point away from the interior.
        const Vec2 mid = 0.5 * (cw.vertex(0) + cw.vertex(1));
        QVERIFY(!cw.contains(mid + 0.5 * cw.outwardNormal(0)));
        QVERIFY(cw.contains(mid - 0.5 * cw.outwardNormal(0)));
    }

    void transformRotatesThenTranslates() {
        const Polygon r = libraryShape("rectangle", {48, 58, 0, 0}).transformed(90.0, {100, 50});
        QCOMPARE(r.boundingBoxMax().x - r.boundingBoxMin().x, 58.0);
        QCOMPARE(r.boundingBoxMax().y - r.boundingBoxMin().y, 48.0);
        QVERIFY(r.contains({100, 50}));
        QVERIFY(qAbs(r.area() - 48.0 * 58.0) < 1e-9);
    }

    void arcLengthRoundTrip() {
        const Polygon c = libraryShape("C", defaultShapeSize("C"));
        for (double s = 0; s < c.perimeter(); s += 7.3) {
            const auto q = c.nearestOutlinePoint(c.pointAtArcLength(s));
            QVERIFY(qAbs(q.arcLength - s) < 1e-9);
            QVERIFY(q.distance < 1e-9);
        }
    }

    void offsetOutlineOfSquare() {
        const Polygon sq({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
        const auto out = sq.offsetOutline(2.0);
        QCOMPARE(int(out.size()), 4);
        QCOMPARE(out[0].x, -2.0);
        QCOMPARE(out[0].y, -2.0);
        QCOMPARE(out[2].x, 12.0);
        QCOMPARE(out[2].y, 12.0);
    }

    void badOutlinesAreRefusedWithAReason_data() {
        QTest::addColumn<QVector<QPointF>>("vertices");
        QTest::addColumn<QString>("reason");
        QTest::newRow("two vertices") << QVector<QPointF>{{0, 0}, {1, 0}} << "at least 3 vertices";
        QTest::newRow("collinear") << QVector<QPointF>{{0, 0}, {1, 0}, {2, 0}} << "no area";
        QTest::newRow("repeated vertex")
            << QVector<QPointF>{{0, 0}, {0, 0}, {1, 0}, {0, 1}} << "repeats the next vertex";
        QTest::newRow("bow tie") << QVector<QPointF>{{0, 0}, {10, 10}, {10, 0}, {0, 10}}
                                 << "intersects itself";
        QTest::newRow("NaN") << QVector<QPointF>{{0, 0}, {qQNaN(), 0}, {0, 1}}
                             << "not a finite number";
        QTest::newRow("vertex beyond any stage")
            << QVector<QPointF>{{0, 0}, {1e300, 0}, {0, 20}} << "more than 1 km from the origin";
        QTest::newRow("spike folds back")
            << QVector<QPointF>{{0, 0}, {10, 0}, {5, 0}, {5, 5}} << "fold back";
    }
    void badOutlinesAreRefusedWithAReason() {
        QFETCH(QVector<QPointF>, vertices);
        QFETCH(QString, reason);
        std::vector<Vec2> v;
        for (auto p : vertices) v.push_back({p.x(), p.y()});
        const auto problem = Polygon::problemWith(v);
        QVERIFY(problem.has_value());
        QVERIFY2(QString::fromStdString(*problem).contains(reason), problem->c_str());
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, Polygon{v});
    }

    void shapeSizesThatMakeNoOutline() {
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, libraryShape("cross", {60, 60, 70, 0}));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, libraryShape("star", {0, 60, 0, 0}));
    }
};

QTEST_APPLESS_MAIN(TestGeometry)
#include "test_geometry.moc"
