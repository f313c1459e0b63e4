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
        // The paper's four shapes with its four orientations and discrete rules; the general
        // shapes need the continuous percept (below).
        QTest::addColumn<QString>("shape");
        for (const auto& n : {"rectangle", "cross", "C", "L"}) QTest::newRow(n) << QString(n);
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

    void continuousPerceptFollowsEveryLibraryShapeAtAnyTurn_data() {
        QTest::addColumn<QString>("shape");
        QTest::addColumn<double>("turn");
        for (const auto& n : libraryShapeNames())
            for (double turn : {0.0, 17.0, 133.0, 251.0})
                QTest::newRow((n + " " + std::to_string(int(turn))).c_str())
                    << QString::fromStdString(n) << turn;
    }
    void continuousPerceptFollowsEveryLibraryShapeAtAnyTurn() {
        // 36 orientations every 10 degrees, perceived ideally (the nearest trained one), the
        // continuous rule steering: every library shape at any turn gets round, close to its
        // contour, and the tangent rule does the following.
        QFETCH(QString, shape);
        QFETCH(double, turn);
        const std::string name = shape.toStdString();
        const Polygon outline =
            libraryShape(name, defaultShapeSize(name)).transformed(turn, {150, 150});
        std::vector<double> every10;
        for (int i = 0; i < 36; ++i) every10.push_back(std::fmod(270.0 + 10.0 * i, 360.0));
        OracleRig rig(paperClassesWithRegions(every10));
        rig.world.perceiveIdeally(outline);
        Rig r = rig.rig();
        TrialSetup s = setupFor(outline, FollowingMode::Active);
        s.settings.percept = PerceptKind::Continuous;
        const TrialResult t = runTrial(r, rig.world.classifier, rig.world.classes, outline, s);
        QVERIFY2(t.completed(), t.detail.c_str());
        QVERIFY2(t.meanContourDistance_mm < 1.5,
                 qPrintable(QString::number(t.meanContourDistance_mm)));
        const auto tangent = std::count_if(t.taps.begin(), t.taps.end(), [](const FollowedTap& f) {
            return f.decision.rule == RuleId::ContinuousFollow;
        });
        QVERIFY(tangent > static_cast<long>(t.taps.size()) / 2);
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
        // The trial says so: it got no further than that corner, and round none.
        QCOMPARE(int(t.furthest.kind), int(PlaceKind::ConvexCorner));
        QCOMPARE(t.furthest.corner, (Vec2{174, 121}));
        QCOMPARE(t.cornersRounded.convex + t.cornersRounded.concave, 0);
        QVERIFY2(t.detail.find("furthest") != std::string::npos &&
                     t.detail.find("the convex corner (174, 121)") != std::string::npos,
                 t.detail.c_str());
    }

    void placesOnTheContourAreJudgedFromTheOutline() {
        // The L (60 x 60, arm 20, at the origin): five convex corners and one concave, at
        // (-10, -10). Near means within half the classes' window, 9 mm for the paper's 18 x 1 mm.
        const Polygon l = libraryShape("L", defaultShapeSize("L"));
        const CornerCriteria c = cornerCriteria(paperClassesWithRegions());
        QCOMPARE(c.reach_mm, 9.0);
        QCOMPARE(c.minTurn_deg, 45.0);
        int convex = 0, concave = 0;
        for (std::size_t i = 0; i < l.size(); ++i) {
            const double turn = l.turnDeg(i);
            QVERIFY(std::abs(std::abs(turn) - 90.0) < 1e-9);
            ++(turn > 0 ? convex : concave);
            QVERIFY(std::abs(l.arcLengthOfVertex(i) -
                             l.nearestOutlinePoint(l.vertex(i)).arcLength) < 1e-9 ||
                    i == 0);
        }
        QCOMPARE(convex, 5);
        QCOMPARE(concave, 1);
        auto placeOf = [&](Vec2 p) {
            const auto o = l.nearestOutlinePoint(p);
            return contourPlace(l, o.point, o.arcLength, c);
        };
        // Counter-clockwise, the tip comes along the top of the horizontal arm (leftward) to the
        // concave corner, then goes up the inner vertical edge.
        const ContourPlace shortOf = placeOf({-5, -10});
        QCOMPARE(int(shortOf.kind), int(PlaceKind::ConcaveCorner));
        QCOMPARE(shortOf.corner, (Vec2{-10, -10}));
        QCOMPARE(shortOf.pastCorner_mm, -5.0);
        QCOMPARE(describePlace(shortOf),
                 std::string("5 mm short of the concave corner (-10, -10)"));
        const ContourPlace past = placeOf({-10, -4});
        QCOMPARE(int(past.kind), int(PlaceKind::ConcaveCorner));
        QCOMPARE(past.pastCorner_mm, 6.0);
        QCOMPARE(describePlace(past), std::string("6 mm past the concave corner (-10, -10)"));
        // Exactly at a convex corner; within the reach and just beyond it.
        QCOMPARE(describePlace(placeOf({-30, -30})),
                 std::string("at the convex corner (-30, -30)"));
        QCOMPARE(int(placeOf({-30, -21.5}).kind), int(PlaceKind::ConvexCorner));     // 8.5 mm
        QCOMPARE(int(placeOf({-30, -20.9}).kind), int(PlaceKind::AwayFromCorners));  // 9.1 mm
        const ContourPlace away = placeOf({-30, 0});  // 30 mm from (-30, 30) and (-30, -30)
        QCOMPARE(int(away.kind), int(PlaceKind::AwayFromCorners));
        QCOMPARE(describePlace(away), std::string("away from corners, at (-30, 0)"));

        // Gentle bends are no corners: a 64-gon circle has none for four orientations, and eight
        // orientations count the octagon's 45 degree turns.
        std::vector<Vec2> circle;
        for (int i = 0; i < 64; ++i) circle.push_back(15.0 * directionFromDegrees(i * 360.0 / 64));
        const Polygon round(circle);
        QCOMPARE(int(contourPlace(round, round.vertex(3), round.arcLengthOfVertex(3), c).kind),
                 int(PlaceKind::AwayFromCorners));
        ClassSet eight;
        eight.orientationsDeg = {0, 45, 90, 135, 180, 225, 270, 315};
        QCOMPARE(cornerCriteria(eight).minTurn_deg, 22.5);
        ClassSet one;
        one.orientationsDeg = {270};
        QCOMPARE(cornerCriteria(one).minTurn_deg, 180.0);  // nothing is a corner
    }

    void cornersRoundedAreCountedFromProgress() {
        // A 40 x 40 square started in the middle of its lower edge: corners 20, 60, 100 and 140
        // mm ahead. A corner counts as got round once the tip went more than 9 mm past it.
        const Polygon square({{0, 0}, {40, 0}, {40, 40}, {0, 40}});
        const CornerCriteria c{45.0, 9.0};
        const double startArc = 20.0;
        auto judged = [&](std::vector<double> progress, TrialEnd end) {
            TrialResult r;
            r.end = end;
            for (double p : progress) {
                FollowedTap t;
                t.progress_mm = p;
                r.taps.push_back(t);
            }
            judgePlaces(square, startArc, c, r);
            return r;
        };
        TrialResult r = judged({0, 2, 4, 29, 27}, TrialEnd::LostOutside);  // 9 mm past: not round
        QCOMPARE(r.furthestProgress_mm, 29.0);
        QCOMPARE(r.furthest.point, (Vec2{40, 9}));
        QCOMPARE(int(r.furthest.kind), int(PlaceKind::ConvexCorner));
        QCOMPARE(r.furthest.pastCorner_mm, 9.0);
        QCOMPARE(r.cornersRounded.convex, 0);
        r = judged({0, 29.5, 70}, TrialEnd::LostPlaneOrAir);
        QCOMPARE(r.cornersRounded.convex, 2);
        QCOMPARE(r.furthest.point, (Vec2{30, 40}));  // 10 mm past (40, 40): beyond its reach
        QCOMPARE(int(r.furthest.kind), int(PlaceKind::AwayFromCorners));
        // Backwards from the start: the furthest point is the start itself.
        r = judged({0, -2, -4}, TrialEnd::LostOutside);
        QCOMPARE(r.furthest.point, (Vec2{20, 0}));
        QCOMPARE(int(r.furthest.kind), int(PlaceKind::AwayFromCorners));
        // A completed trial got round every corner once, however far it went.
        r = judged({0, 80, 161}, TrialEnd::Completed);
        QCOMPARE(r.cornersRounded.convex, 4);
        QCOMPARE(r.cornersRounded.concave, 0);
        r = judged({}, TrialEnd::DeviceError);  // no tap: it got no further than the start
        QCOMPARE(r.furthestProgress_mm, 0.0);
        QCOMPARE(r.cornersRounded.convex, 0);
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
        // A spike pointing down: its sides face mostly left and right; the start is on the one
        // facing down most (both equally: the lower middle, at y = -15).
        QCOMPARE(lowerEdgeStart(Polygon({{0, -30}, {5, 0}, {-5, 0}}), {}).y, -15.0);
        QVERIFY(lowerEdgeStart(diamond, {}).y < 0);  // 45 degrees still counts as the lower edge
    }

    void pathMetrics() {
        const Polygon square({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
        TrialResult r;
        measurePath(square, {{5, -1}, {5, 11}}, 3.0, 0.0, r);
        QCOMPARE(r.meanContourDistance_mm, 1.0);
        QCOMPARE(r.maxContourDistance_mm, 1.0);
        QVERIFY(r.coverage > 0.2 && r.coverage < 0.4);  // two 5.7 mm stretches of 40 mm
        measurePath(square, {}, 3.0, 0.0, r);
        QCOMPARE(r.coverage, 0.0);
    }
};

QTEST_APPLESS_MAIN(TestContourFollower)
#include "test_contour_follower.moc"
