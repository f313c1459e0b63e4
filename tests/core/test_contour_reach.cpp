// What a round contact patch can resolve of an outline: sharp right angles and features wider
// than the patch are within reach; notches, slots and teeth narrower than it are found by place
// and kind, at any pose; degenerate radii and objects smaller than the patch stay well defined.
#include <QtTest>

#include "core/control/ContourFollower.h"
#include "core/fingertip/FingertipContactModel.h"
#include "core/geometry/ContourReach.h"
#include "core/geometry/ShapeLibrary.h"
#include "core/scene/Scene.h"

using namespace activetouch;

namespace {

/// A 60 x 30 block with a slot `width` wide and `depth` deep cut down from the middle of its top.
Polygon slotted(double width, double depth) {
    const double h = 0.5 * width;
    return Polygon({{-30, 0},
                    {30, 0},
                    {30, 30},
                    {h, 30},
                    {h, 30 - depth},
                    {-h, 30 - depth},
                    {-h, 30},
                    {-30, 30}});
}

/// A 60 x 20 block with `teeth` teeth `width` wide and `height` tall along its top, as far apart
/// as they are wide, centred.
Polygon toothed(int teeth, double width, double height) {
    std::vector<Vec2> v{{-30, 0}, {30, 0}, {30, 20}};
    const double span = (2 * teeth - 1) * width;
    for (int i = teeth - 1; i >= 0; --i) {
        const double left = -0.5 * span + 2 * i * width;
        v.push_back({left + width, 20});
        v.push_back({left + width, 20 + height});
        v.push_back({left, 20 + height});
        v.push_back({left, 20});
    }
    v.push_back({-30, 20});
    return Polygon(v);
}

Vec2 sampleAt(const Polygon& p, const ContourReach& r, std::size_t i) {
    return p.pointAtArcLength(double(i) * p.perimeter() / double(r.samples()));
}

}  // namespace

class TestContourReach : public QObject {
    Q_OBJECT
private slots:
    void paperShapesAreWithinReach() {
        // Right angles, inside and out, and edges far longer than the patch: all of it.
        for (const char* name : {"rectangle", "cross", "C", "L"}) {
            const Polygon p = libraryShape(name, defaultShapeSize(name));
            const ContourReach reach(p, 4.5);
            QVERIFY2(reach.stretches().empty(), name);
            QCOMPARE(reach.reachableFraction(), 1.0);
        }
    }

    void aSlotNarrowerThanThePatchIsOneInwardStretchAtItsBottom() {
        const Polygon p = slotted(3.0, 15.0);
        const ContourReach reach(p, 4.0);
        QCOMPARE(int(reach.stretches().size()), 1);
        const OutOfReach& o = reach.stretches().front();
        QCOMPARE(o.kind, OutOfReach::Kind::Inward);
        QVERIFY2(std::abs(o.middle.x) < 1.6 && std::abs(o.middle.y - 15.0) < 0.5,
                 qPrintable(QString("middle (%1, %2)").arg(o.middle.x).arg(o.middle.y)));
        QVERIFY(o.mouth_mm < 3.5);  // the two walls, a sample apart in depth at most
        // Both walls down to where the patch's rim reaches, and the bottom: most of the 33 mm.
        QVERIFY2(o.length_mm > 20.0 && o.length_mm < 33.5,
                 qPrintable(QString::number(o.length_mm)));
        // The bottom lies 15 mm down; the disc stays at the mouth, past the search's 2 radii.
        QVERIFY(o.depthCapped);
        QCOMPARE(o.depth_mm, 8.0);
        // The rest of the outline is within reach, and the fraction says how much is not.
        QCOMPARE(reach.reachableFraction(), 1.0 - o.length_mm / p.perimeter());
    }

    void aSlotWiderThanThePatchIsFollowedRightIn() {
        const ContourReach reach(slotted(12.0, 15.0), 4.0);
        QVERIFY(reach.stretches().empty());
    }

    void teethNarrowerThanThePatchAlternateToothAndGap() {
        const Polygon p = toothed(5, 2.0, 5.0);
        const ContourReach reach(p, 4.0);
        int inward = 0, outward = 0;
        for (const OutOfReach& o : reach.stretches()) {
            (o.kind == OutOfReach::Kind::Inward ? inward : outward)++;
            QVERIFY2(o.middle.y > 19.9 && std::abs(o.middle.x) < 10.0,
                     qPrintable(QString("(%1, %2)").arg(o.middle.x).arg(o.middle.y)));
        }
        QVERIFY2(outward >= 5 && inward >= 4,
                 qPrintable(QString("%1 teeth, %2 gaps").arg(outward).arg(inward)));
        // Every tooth's tip is out of reach; the block's bottom edge is not.
        for (std::size_t i = 0; i < reach.samples(); ++i) {
            const Vec2 q = sampleAt(p, reach, i);
            if (q.y > 24.99) QVERIFY(!reach.reachable(i));
            if (q.y < 0.01 && std::abs(q.x) < 25.0) QVERIFY(reach.reachable(i));
        }
        // The same teeth twice as wide as the patch are followed.
        QVERIFY(ContourReach(toothed(2, 10.0, 5.0), 4.0).stretches().empty());
    }

    void aSpikeSharperThanTheToleranceIsAnOutwardStretch() {
        const Polygon p({{-20, 0}, {20, 0}, {20, 20}, {1.5, 20}, {0, 40}, {-1.5, 20}, {-20, 20}});
        const ContourReach reach(p, 4.0);
        QVERIFY(!reach.stretches().empty());
        bool tip = false;
        for (const OutOfReach& o : reach.stretches())
            tip = tip || (o.kind == OutOfReach::Kind::Outward && o.middle.y > 30.0);
        QVERIFY(tip);
    }

    void theReachDoesNotDependOnThePose() {
        const Polygon p = slotted(3.0, 15.0);
        const double here = ContourReach(p, 4.0).reachableFraction();
        for (double turn : {17.0, 90.0, 233.5}) {
            const Polygon moved = p.transformed(turn, {311.0, -47.0});
            const double there = ContourReach(moved, 4.0).reachableFraction();
            QVERIFY2(std::abs(there - here) <= 2.0 / double(ContourReach(moved, 4.0).samples()),
                     qPrintable(QString("%1 vs %2 at %3 deg").arg(there).arg(here).arg(turn)));
        }
    }

    void degenerateRadiiAndTinyObjectsStayDefined() {
        const Polygon slot = slotted(3.0, 15.0);
        for (double r : {0.0, -1.0, std::nan("")}) {
            const ContourReach reach(slot, r);
            QCOMPARE(reach.reachableFraction(), 1.0);
            QVERIFY(reach.stretches().empty());
        }
        // A 3 mm square under a 4 mm patch: no disc fits on it, so none of it is resolved.
        const Polygon tiny({{0, 0}, {3, 0}, {3, 3}, {0, 3}});
        const ContourReach reach(tiny, 4.0);
        QCOMPARE(reach.reachableFraction(), 0.0);
        QCOMPARE(int(reach.stretches().size()), 1);
        QCOMPARE(reach.stretches().front().kind, OutOfReach::Kind::Outward);
        QVERIFY(reach.stretches().front().depthCapped);
        QVERIFY(std::abs(reach.stretches().front().length_mm - 12.0) < 1e-9);
        // A long outline is judged in at most kMaxSamples points.
        const Polygon huge({{0, 0}, {20000, 0}, {20000, 10}, {0, 10}});
        QCOMPARE(ContourReach(huge, 4.0).samples(), ContourReach::kMaxSamples);
    }

    void coverageCountsOnlyTheContourWithinReach() {
        const Polygon p = slotted(3.0, 15.0);
        // A path round the block's outside that cuts across the slot's mouth.
        std::vector<Vec2> path;
        for (double x = -30; x <= 30; x += 1.0) path.push_back({x, 0});
        for (double y = 0; y <= 30; y += 1.0) path.push_back({30, y});
        for (double x = 30; x >= -30; x -= 1.0) path.push_back({x, 30});
        for (double y = 30; y >= 0; y -= 1.0) path.push_back({-30, y});
        TrialResult blind, judged;
        measurePath(p, path, 3.0, 0.0, blind);
        measurePath(p, path, 3.0, 4.0, judged);
        QCOMPARE(blind.reachable, 1.0);
        QVERIFY(blind.coverage < 0.9);  // 24 mm of the slot's 33 lie beyond the radius
        QVERIFY(judged.reachable < 0.9);
        QVERIFY2(judged.coverage > 0.99, qPrintable(QString::number(judged.coverage)));
    }

    void thePaperFingertipsPatchOnAnEdge() {
        // The paper's fingertip pressed on an edge until its contact threshold: a patch several
        // millimetres across, growing with the threshold and never past the stroke's.
        SceneSpec scene;
        scene.fingertip = loadFingertip(scene.fingertipName, "", "test", "/fingertip");
        const FingertipContactModel model(scene.fingertip);
        const double r =
            model.edgeContactRadius(scene.tap.contactThreshold, scene.strokeLimitDepth());
        QVERIFY2(r > 1.5 && r < 8.0, qPrintable(QString::number(r)));
        QVERIFY(model.edgeContactRadius(4 * scene.tap.contactThreshold, scene.strokeLimitDepth()) >
                r);
        QCOMPARE(model.edgeContactRadius(1e9, scene.strokeLimitDepth()),
                 model.footprintHalfWidth(scene.strokeLimitDepth()));
        QCOMPARE(model.footprintHalfWidth(-1.0), 0.0);
        // The body is a cylinder of radius R: pressed d in, its footprint across the axis is
        // 2 sqrt(2 R d - d^2) wide, the narrowest way (within a grid step).
        const double R = scene.fingertip.radius, d = 1.0;
        QVERIFY(std::abs(model.footprintHalfWidth(d) - std::sqrt(2 * R * d - d * d)) <=
                scene.fingertip.gridStep);
    }
};

QTEST_APPLESS_MAIN(TestContourReach)
#include "test_contour_reach.moc"
