// The contour follower's trials on a rig with ideal (oracle) perception: completion, every way a
// trial ends, and what a trial reports.
#include <QtTest>

#include "core/geometry/ShapeLibrary.h"
#include "support/OracleRig.h"

using namespace activetouch;
using namespace activetouch::test;

namespace {
Polygon rectangleAt(Vec2 centre) {
    return libraryShape("rectangle", {48, 58, 0, 0}).transformed(0, centre);
}
TrialSetup setupFor(const Polygon& outline, FollowingMode mode) {
    TrialSetup s;
    s.mode = mode;
    s.valid = {-2.0, 2.0, -4.0, 4.0};
    s.start = lowerEdgeStart(outline, s.valid);
    return s;
}
}  // namespace

class TestContourFollower : public QObject {
    Q_OBJECT
private slots:
    void idealPerceptionCompletesEveryLibraryShape_data() {
        QTest::addColumn<QString>("shape");
        for (const auto& n : libraryShapeNames())
            QTest::newRow(n.c_str()) << QString::fromStdString(n);
    }
    void idealPerceptionCompletesEveryLibraryShape() {
        QFETCH(QString, shape);
        const Polygon outline =
            libraryShape(shape.toStdString(), defaultShapeSize(shape.toStdString()))
                .transformed(0, {150, 150});
        OracleRig rig(paperClassesWithRegions());
        rig.world.perceiveIdeally(outline);
        Rig r = rig.rig();
        const TrialResult t = runTrial(r, rig.world.classifier, rig.world.classes, outline,
                                       setupFor(outline, FollowingMode::Active));
        QVERIFY2(t.completed(), t.detail.c_str());
        QVERIFY(t.progress_mm >= outline.perimeter());
        QVERIFY(distance(t.taps.back().record.pose, t.taps.front().record.pose) <= 4.0);
        QVERIFY(t.coverage > 0.95);
        QVERIFY2(t.maxContourDistance_mm < 6.0,
                 qPrintable(QString::number(t.maxContourDistance_mm)));
        QCOMPARE(t.robotTime_s, rig.world.clock);  // taps and moves, all on the robot clock
        QCOMPARE(t.path().size(), t.taps.size());
    }

    void passiveWithIdealPerceptionStillLosesConvexCorners() {
        // Without repositioning, the tip keeps its offset: past a convex corner it reads air and
        // keeps its heading, away from the object.
        const Polygon outline = rectangleAt({150, 150});
        OracleRig rig(paperClassesWithRegions());
        rig.world.perceiveIdeally(outline);
        TrialSetup s = setupFor(outline, FollowingMode::Passive);
        s.start = s.start + Vec2{0, -2.5};  // a little outside: the passive loop never corrects it
        Rig r = rig.rig();
        const TrialResult t = runTrial(r, rig.world.classifier, rig.world.classes, outline, s);
        QVERIFY(!t.completed());
        // It went wrong at the lower right corner, after following the lower edge.
        const Vec2 last = t.taps.back().record.pose;
        QVERIFY2(last.x > 174.0, qPrintable(QString("lost at (%1, %2)").arg(last.x).arg(last.y)));
    }

    void everyEndingIsReportedWithItsTaps_data() {
        QTest::addColumn<int>(
            "percept");  // class the oracle always reports, or -1 for special set-ups
        QTest::addColumn<int>("end");
        ClassSet cs;
        QTest::newRow("always the lower edge in range: runs off the end")
            << cs.classOf(0, 10) << int(TrialEnd::LostOutside);
        QTest::newRow("always the lower edge, on the air side: walks inward")
            << cs.classOf(0, 13) << int(TrialEnd::LostInside);
        QTest::newRow("always air") << cs.classOf(0, 18) << int(TrialEnd::LostPlaneOrAir);
    }
    void everyEndingIsReportedWithItsTaps() {
        QFETCH(int, percept);
        QFETCH(int, end);
        const Polygon outline = rectangleAt({150, 150});
        OracleRig rig(paperClassesWithRegions());
        rig.world.oracle = [percept](Vec2) { return percept; };
        TrialSetup s = setupFor(outline, FollowingMode::Active);
        s.settings.lostPlaneOrAirTaps = 3;
        Rig r = rig.rig();
        const TrialResult t = runTrial(r, rig.world.classifier, rig.world.classes, outline, s);
        QCOMPARE(int(t.end), end);
        QVERIFY(!t.taps.empty());
        QVERIFY(!t.detail.empty());
        QVERIFY(t.robotTime_s > 0);
    }

    void tapCapEndsATrialThatNeverArrives() {
        const Polygon outline = rectangleAt({150, 150});
        OracleRig rig(paperClassesWithRegions());
        rig.world.perceiveIdeally(outline);
        TrialSetup s = setupFor(outline, FollowingMode::Active);
        s.settings.tapCapPerimeters = 0.2;  // 0.2 x 212 mm / 2 mm = 22 taps
        Rig r = rig.rig();
        const TrialResult t = runTrial(r, rig.world.classifier, rig.world.classes, outline, s);
        QCOMPARE(int(t.end), int(TrialEnd::TapCap));
        QCOMPARE(int(t.taps.size()), 22);
    }

    void deviceErrorEndsCleanlyAndKeepsTheTaps() {
        const Polygon outline = rectangleAt({150, 150});
        OracleRig rig(paperClassesWithRegions());
        rig.world.perceiveIdeally(outline);
        rig.world.failAfterMoves = 6;  // the move to the start plus five following moves succeed
        Rig r = rig.rig();
        int seen = 0;
        const TrialResult t =
            runTrial(r, rig.world.classifier, rig.world.classes, outline,
                     setupFor(outline, FollowingMode::Active), [&](const FollowedTap&) {
                         ++seen;
                         return true;
                     });
        QCOMPARE(int(t.end), int(TrialEnd::DeviceError));
        QVERIFY(QString::fromStdString(t.detail).contains("serial port vanished"));
        QCOMPARE(int(t.taps.size()), 6);
        QCOMPARE(seen, 6);
    }

    void cancelStopsAfterTheCurrentTap() {
        const Polygon outline = rectangleAt({150, 150});
        OracleRig rig(paperClassesWithRegions());
        rig.world.perceiveIdeally(outline);
        Rig r = rig.rig();
        int seen = 0;
        const TrialResult t = runTrial(r, rig.world.classifier, rig.world.classes, outline,
                                       setupFor(outline, FollowingMode::Active),
                                       [&](const FollowedTap&) { return ++seen < 10; });
        QCOMPARE(int(t.end), int(TrialEnd::Cancelled));
        QCOMPARE(int(t.taps.size()), 10);
    }

    void progressCannotBeEarnedByDithering() {
        // A tip that steps back and forth along an edge makes no progress.
        const Polygon outline = rectangleAt({150, 150});
        OracleRig rig(paperClassesWithRegions());
        ClassSet cs;
        int n = 0;
        rig.world.oracle = [&](Vec2) {
            return (n++ % 2) ? cs.classOf(0, 10) : cs.classOf(2, 10);
        };  // lower, upper, lower...
        TrialSetup s = setupFor(outline, FollowingMode::Active);
        s.settings.tapCapPerimeters = 1.0;
        Rig r = rig.rig();
        const TrialResult t = runTrial(r, rig.world.classifier, rig.world.classes, outline, s);
        QCOMPARE(int(t.end), int(TrialEnd::TapCap));
        QVERIFY(std::abs(t.progress_mm) <= 2.0);
    }

    void startPoses() {
        const Polygon cross =
            libraryShape("cross", defaultShapeSize("cross")).transformed(0, {150, 150});
        const Vec2 start = lowerEdgeStart(cross, {-2.0, 2.0});
        QCOMPARE(start.x, 150.0);  // the middle of the bottom arm's end
        QCOMPARE(start.y, 120.0);
        FollowingSettings s;
        QVERIFY(startProblem(cross, start, s).empty());
        QVERIFY(QString::fromStdString(startProblem(cross, {150, 100}, s))
                    .contains("outside the object"));
        QVERIFY(QString::fromStdString(startProblem(cross, {150, 150}, s))
                    .contains("inside the object"));
        const Polygon diamond({{0, -10}, {10, 0}, {0, 10}, {-10, 0}});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 lowerEdgeStart(Polygon({{0, -30}, {5, 0}, {-5, 0}}),
                                                {}));  // a spike: its sides face left and right
        QVERIFY(lowerEdgeStart(diamond, {}).y < 0);    // 45 degrees still counts as the lower edge
    }

    void pathMetrics() {
        const Polygon square({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
        TrialResult r;
        measurePath(square, {{5, -1}, {5, 11}}, 3.0, r);
        QCOMPARE(r.meanContourDistance_mm, 1.0);
        QCOMPARE(r.maxContourDistance_mm, 1.0);
        QVERIFY(r.coverage > 0.2 && r.coverage < 0.4);  // two 5.7 mm stretches of 40 mm
        measurePath(square, {}, 3.0, r);
        QCOMPARE(r.coverage, 0.0);
    }
};

QTEST_APPLESS_MAIN(TestContourFollower)
#include "test_contour_follower.moc"
