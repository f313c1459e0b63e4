// The ideal fingertip physics: what comes out of geometry alone.
#include <QtTest>
#include <limits>
#include <numeric>

#include "core/fingertip/FingertipContactModel.h"
#include "core/scene/Scene.h"
#include "core/validation/ClassRegions.h"

using namespace activetouch;

namespace {
const FingertipContactModel& model() {
    static const FingertipContactModel m(loadFingertip("icub_fingertip_2010", ".", "test", ""));
    return m;
}
const Polygon& bigSquare() {
    static const Polygon p({{-500, -500}, {500, -500}, {500, 500}, {-500, 500}});
    return p;
}
// Object occupying y < 0 (an edge along x with outward normal +y, "upper").
const Polygon& lowerHalf() {
    static const Polygon p({{-500, -500}, {500, -500}, {500, 0}, {-500, 0}});
    return p;
}
double sum(const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0);
}
}  // namespace

class TestContactModel : public QObject {
    Q_OBJECT
private slots:
    void firstContactPointTouchesFirst() {
        // The fingertip centre is the tip's lowest point: nothing of the body lies below it.
        QCOMPARE(model().surfaceHeightAt({0, 0}), 0.0);
        for (double x = -8; x <= 8; x += 0.5)
            for (double y = -12; y <= 8; y += 0.5)
                QVERIFY(model().surfaceHeightAt({x, y}) >= -1e-9);
    }

    void pressureGrowsWithIndentationAndMatchesTotal() {
        auto c = model().contactAt(bigSquare(), {0, 0});
        std::vector<double> p(12);
        double previous = 0.0;
        for (double d = 0.1; d <= 3.0; d += 0.1) {
            c.taxelPressures(d, p.data());
            QVERIFY(sum(p) > previous);
            QVERIFY(std::abs(sum(p) - c.totalPressure(d)) < 1e-3 * sum(p));
            previous = sum(p);
        }
        const auto depth = c.depthReaching(250.0, 3.0);
        QVERIFY(depth.has_value());
        QVERIFY(std::abs(c.totalPressure(*depth) - 250.0) < 1e-6);
    }

    void noObjectNoPressure() {
        const Polygon far({{400, 400}, {450, 400}, {450, 450}, {400, 450}});
        auto c = model().contactAt(far, {0, 0});
        std::vector<double> p(12, 1.0);
        c.taxelPressures(3.0, p.data());
        QCOMPARE(sum(p), 0.0);
        QVERIFY(!c.depthReaching(1.0, 3.0).has_value());
    }

    void edgeMovesPressureContinuously() {
        // Pose steps far below the grid step change the readings only a little: no cell jumps.
        std::vector<double> a(12), b(12);
        for (double y = -4.0; y <= 4.0; y += 0.37) {
            auto ca = model().contactAt(lowerHalf(), {0, y});
            auto cb = model().contactAt(lowerHalf(), {0, y + 0.01});
            ca.taxelPressures(1.5, a.data());
            cb.taxelPressures(1.5, b.data());
            for (int k = 0; k < 12; ++k)
                QVERIFY2(std::abs(a[k] - b[k]) < 1.0,
                         qPrintable(QString("y %1 taxel %2").arg(y).arg(k)));
        }
    }

    void edgeCutsOffTheTaxelsBeyondIt() {
        // Tip centre 3 mm beyond an edge: only taxels over the object read pressure.
        auto c = model().contactAt(lowerHalf(), {0, 3.0});
        std::vector<double> p(12);
        c.taxelPressures(2.0, p.data());
        QVERIFY(sum(p) > 0);
        for (int k = 0; k < 12; ++k) {
            const double y = model().projectedTaxels()[k].y + 3.0;
            if (y > 4.0)
                QVERIFY2(p[k] < 0.5,
                         qPrintable(QString("taxel %1 beyond the edge reads %2").arg(k).arg(p[k])));
        }
    }

    void regionsComeFromGeometryAndDifferByOrientation() {
        ClassSet cs;
        TapSpec tap;
        tap.contactThreshold = 250.0;
        const auto regions = computeClassRegions(model(), cs, tap, 3.0);
        int plane = 0, air = 0;
        bool differ = false;
        for (int o = 0; o < 4; ++o) {
            QCOMPARE(regions[cs.classOf(o, 1)], Region::Plane);  // deep on the object
            QCOMPARE(regions[cs.classOf(o, 9)], Region::Edge);  // half a millimetre inside the edge
            for (int p = 1; p <= 18; ++p) {
                plane += regions[cs.classOf(o, p)] == Region::Plane;
                air += regions[cs.classOf(o, p)] == Region::Air;
                differ = differ || regions[cs.classOf(o, p)] != regions[cs.classOf(0, p)];
            }
        }
        QVERIFY(plane > 4 && air > 4);
        QVERIFY2(differ,
                 "a tilted tip should give different region maps for different orientations");
    }

    void noiseFloorIsMeasuredFromTapsThatTouchedNothing() {
        ClassSet cs;
        TapSpec tap;
        tap.contactThreshold = 250.0;
        const auto ideal = idealClassContacts(model(), cs, tap, 3.0);
        const int air = cs.classOf(0, 18), edge = cs.classOf(0, 9);
        QCOMPARE(ideal[air].peak, 0.0);
        QVERIFY(ideal[edge].peak > 20.0);
        // Twenty taps in the air peaking at 1..20 counts, and pressed taps that must not count.
        std::vector<Tap> taps;
        for (int peak = 1; peak <= 20; ++peak) {
            Tap t(50, 12);
            t.at(peak % 50, peak % 12) = peak;
            taps.push_back(t);
        }
        Tap pressed(50, 12);
        pressed.at(10, 3) = 240.0;
        std::vector<ClassTap> labelled;
        for (const Tap& t : taps) labelled.push_back({air, &t});
        for (int i = 0; i < 30; ++i) labelled.push_back({edge, &pressed});
        const auto floor = measureNoiseFloor(ideal, labelled);
        QVERIFY(floor.has_value());
        QCOMPARE(floor->taps, 20);
        QCOMPARE(floor->counts, 19.0);  // nearest-rank 95th percentile of 1..20
    }

    void noiseFloorNeedsTapsThatTouchedNothing_data() {
        QTest::addColumn<int>("which");
        QTest::newRow("no taps") << 0;
        QTest::newRow("only pressed taps") << 1;
        QTest::newRow("empty taps and unknown classes") << 2;
        QTest::newRow("unreadable taps in the air") << 3;
    }
    void noiseFloorNeedsTapsThatTouchedNothing() {
        QFETCH(int, which);
        ClassSet cs;
        TapSpec tap;
        tap.contactThreshold = 250.0;
        const auto ideal = idealClassContacts(model(), cs, tap, 3.0);
        Tap pressed(50, 12), empty, unreadable(50, 12);
        pressed.at(0, 0) = 100.0;
        for (double& v : unreadable.samples) v = std::numeric_limits<double>::quiet_NaN();
        std::vector<ClassTap> labelled;
        if (which == 1) labelled = {{cs.classOf(0, 9), &pressed}, {cs.classOf(2, 1), &pressed}};
        if (which == 2)
            labelled = {{cs.classOf(0, 18), &empty},
                        {-1, &pressed},
                        {cs.classCount(), &pressed},
                        {cs.classOf(0, 18), nullptr}};
        if (which == 3)
            labelled = {{cs.classOf(0, 18), &unreadable}, {cs.classOf(0, 17), &unreadable}};
        QVERIFY(!measureNoiseFloor(ideal, labelled).has_value());
    }

    void classesFainterThanTheNoiseFloorAreAir() {
        // A class whose ideal tap presses a taxel, but less than the floor, cannot be told from
        // air: it is air at that floor and an edge below it; the rest of the map stays.
        ClassSet cs;
        TapSpec tap;
        tap.contactThreshold = 250.0;
        const auto ideal = idealClassContacts(model(), cs, tap, 3.0);
        int faint = -1;
        for (int c = 0; c < cs.classCount(); ++c)
            if (ideal[c].peak > 0.5 && ideal[c].peak < 10.0 && !ideal[c].fullyOnObject &&
                (faint < 0 || ideal[c].peak < ideal[faint].peak))
                faint = c;
        QVERIFY2(faint >= 0, "the tilted tip should graze an edge faintly at some class");
        const auto below = classRegions(ideal, 0.5 * ideal[faint].peak);
        const auto above = classRegions(ideal, ideal[faint].peak + 0.01);
        QCOMPARE(below[faint], Region::Edge);
        QCOMPARE(above[faint], Region::Air);
        for (int c = 0; c < cs.classCount(); ++c)
            if (ideal[c].peak > ideal[faint].peak + 0.01) QCOMPARE(above[c], below[c]);
        QCOMPARE(classRegions(ideal, tap.noiseFloor), computeClassRegions(model(), cs, tap, 3.0));
    }
};

QTEST_APPLESS_MAIN(TestContactModel)
#include "test_contact_model.moc"
