// The perception-action loop's rules table (paper Figure 4), row by row, and repositioning into
// and out of the valid range.
#include <QtTest>

#include "core/control/DecisionRules.h"

using namespace activetouch;

namespace {
Percept edge(double orientationDeg, double offset) {
    Percept p;
    p.region = Region::Edge;
    p.orientationDeg = orientationDeg;
    p.offset_mm = offset;
    return p;
}
Percept region(Region r) {
    Percept p;
    p.region = r;
    return p;
}
bool near(Vec2 a, Vec2 b) {
    return distance(a, b) < 1e-9;
}
}  // namespace

Q_DECLARE_METATYPE(activetouch::Percept)
Q_DECLARE_METATYPE(activetouch::Vec2)

class TestDecisionRules : public QObject {
    Q_OBJECT
    FollowingSettings settings_;  // paper steps: follow 2, reposition 1, plane/air 2
    ValidOffsets valid_{-2.0, 2.0, -4.0, 4.0};

private slots:
    void everyRuleIsInTheTableOnce() {
        const auto& rules = decisionRules();
        QCOMPARE(int(rules.size()), 11);
        for (std::size_t i = 0; i < rules.size(); ++i)
            for (std::size_t j = i + 1; j < rules.size(); ++j) QVERIFY(rules[i].id != rules[j].id);
        for (const auto& r : rules)
            QVERIFY(QString(r.when).size() > 0 && QString(r.then).size() > 0 &&
                    QString(r.name).size() > 0);
    }

    void rulesRowByRow_data() {
        QTest::addColumn<int>("mode");
        QTest::addColumn<Percept>("percept");
        QTest::addColumn<int>("rule");
        QTest::addColumn<Vec2>("move");
        const int A = int(FollowingMode::Active), P = int(FollowingMode::Passive);
        // Memory: last edge = lower (270), heading +x. CCW traversal: along the lower edge is +x,
        // along the right edge +y, upper -x, left -y.
        QTest::newRow("active, lower edge in range: follow +x")
            << A << edge(270, 0.5) << int(RuleId::FollowInRange) << Vec2{2, 0};
        QTest::newRow("active, right edge in range: follow +y")
            << A << edge(0, -1.0) << int(RuleId::FollowInRange) << Vec2{0, 2};
        QTest::newRow("active, upper edge in range: follow -x")
            << A << edge(90, 2.0) << int(RuleId::FollowInRange) << Vec2{-2, 0};
        QTest::newRow("active, left edge in range: follow -y")
            << A << edge(180, -2.0) << int(RuleId::FollowInRange) << Vec2{0, -2};
        QTest::newRow("active, lower edge plane side: + 1 mm out (-y)")
            << A << edge(270, -3.0) << int(RuleId::FollowRepositionOut) << Vec2{2, -1};
        QTest::newRow("active, lower edge air side: + 1 mm in (+y)")
            << A << edge(270, 3.0) << int(RuleId::FollowRepositionIn) << Vec2{2, 1};
        QTest::newRow("active, right edge air side: + 1 mm in (-x)")
            << A << edge(0, 3.5) << int(RuleId::FollowRepositionIn) << Vec2{-1, 2};
        QTest::newRow("active, plane: out along last normal, back")
            << A << region(Region::Plane) << int(RuleId::PlaneStepBack) << Vec2{-2, -2};
        QTest::newRow("active, air: in along last normal, back")
            << A << region(Region::Air) << int(RuleId::AirStepBack) << Vec2{-2, 2};
        QTest::newRow("active, untrusted edge, plane side: as plane")
            << A << edge(180, -6.0) << int(RuleId::UntrustedPlaneSide) << Vec2{-2, -2};
        QTest::newRow("active, untrusted edge, air side: as air")
            << A << edge(180, 6.0) << int(RuleId::UntrustedAirSide) << Vec2{-2, 2};
        QTest::newRow("passive, edge: follow, never reposition")
            << P << edge(270, 6.0) << int(RuleId::PassiveFollow) << Vec2{2, 0};
        QTest::newRow("passive, other edge: follow it")
            << P << edge(0, -6.0) << int(RuleId::PassiveFollow) << Vec2{0, 2};
        QTest::newRow("passive, plane: keep heading")
            << P << region(Region::Plane) << int(RuleId::PassiveKeepHeading) << Vec2{2, 0};
        QTest::newRow("passive, air: keep heading")
            << P << region(Region::Air) << int(RuleId::PassiveKeepHeading) << Vec2{2, 0};
    }
    void rulesRowByRow() {
        QFETCH(int, mode);
        QFETCH(Percept, percept);
        QFETCH(int, rule);
        QFETCH(Vec2, move);
        ShortTermMemory memory;  // lower edge, heading +x
        const Decision d = decide(percept, memory, FollowingMode(mode), settings_, valid_);
        QCOMPARE(int(d.rule), rule);
        QVERIFY2(near(d.move(), move),
                 qPrintable(QString("move (%1, %2)").arg(d.move().x).arg(d.move().y)));
    }

    void repositioningMovesIntoTheValidRangeAndStopsThere() {
        // A straight lower edge at y = 0, tip starting 5 mm inside: ideal perception of the
        // offset; the active rule walks it out 1 mm per tap and then only follows.
        ShortTermMemory memory;
        const ValidOffsets trustAll{-2.0, 2.0, -1e9, 1e9};
        double y = 5.0;  // inside the object (offset -5)
        int repositioned = 0;
        for (int tap = 0; tap < 12; ++tap) {
            const Decision d =
                decide(edge(270, -y), memory, FollowingMode::Active, settings_, trustAll);
            if (d.reposition != Vec2{}) ++repositioned;
            y += d.move().y;
        }
        QCOMPARE(repositioned, 3);  // 5 -> 4 -> 3 -> 2: inside the valid range (-2..2)
        QCOMPARE(y, 2.0);
        // And from the air side.
        y = -4.0;
        for (int tap = 0; tap < 12; ++tap)
            y += decide(edge(270, -y), memory, FollowingMode::Active, settings_, trustAll).move().y;
        QCOMPARE(y, -2.0);
    }

    void memoryConfirmsEdgesBeforeThePlaneAndAirRulesUseThem() {
        ShortTermMemory memory;
        memory.confirmationsNeeded = 2;
        memory.update(edge(0, 0.0), true);  // one right-edge percept: not yet the last edge
        QCOMPARE(memory.lastEdgeDeg, 270.0);
        QVERIFY(near(
            decide(region(Region::Air), memory, FollowingMode::Active, settings_, valid_).move(),
            {-2, 2}));
        memory.update(edge(0, 0.5), true);  // confirmed
        QCOMPARE(memory.lastEdgeDeg, 0.0);
        QVERIFY(near(memory.heading, {0, 1}));
        QVERIFY(near(
            decide(region(Region::Air), memory, FollowingMode::Active, settings_, valid_).move(),
            {-2, -2}));
        // Plane/air percepts and untrusted edges count toward being lost.
        memory.update(region(Region::Air), false);
        memory.update(edge(90, 9.0), false);
        QCOMPARE(memory.planeOrAirRun, 2);
        memory.update(edge(90, 0.0), true);
        QCOMPARE(memory.planeOrAirRun, 0);
    }

    void theTangentRuleFollowsTheAngleAndServoesTheOffset() {
        // A continuous percept at 37 degrees, 0.6 mm on the air side of the valid range's centre:
        // the step goes along the tangent, and back along the normal by the offset.
        Percept p = edge(37.0, 0.6);
        p.continuous = true;
        ShortTermMemory memory;
        const Decision d = decide(p, memory, FollowingMode::Active, settings_, valid_);
        QCOMPARE(int(d.rule), int(RuleId::ContinuousFollow));
        QVERIFY(distance(d.follow, settings_.followStep_mm * followDirection(37.0)) < 1e-12);
        QVERIFY(distance(d.reposition, -0.6 * outwardNormal(37.0)) < 1e-12);
        // Far off: the move back is held to the reposition step.
        Percept far = edge(37.0, -3.5);
        far.continuous = true;
        QVERIFY(std::abs(
                    norm(decide(far, memory, FollowingMode::Active, settings_, valid_).reposition) -
                    settings_.repositionStep_mm) < 1e-12);
        // Recent edges on an arc turning 5 degrees per 2 mm (2.5 per mm, counter-clockwise): the
        // step is turned by half the turn over it, 2.5 degrees.
        for (int i = 0; i < 4; ++i) memory.noteEdgeAt({2.0 * i, 0.0}, 30.0 + 5.0 * i, 4);
        QVERIFY(std::abs(memory.turnDegPerMm() - 2.5) < 1e-12);
        const Decision turned = decide(p, memory, FollowingMode::Active, settings_, valid_);
        QVERIFY(distance(turned.follow, settings_.followStep_mm * followDirection(39.5)) < 1e-12);
        // Across 0/360 the turn is the short way round; a corner's worth is capped.
        ShortTermMemory wrap;
        wrap.noteEdgeAt({0, 0}, 355.0, 4);
        wrap.noteEdgeAt({2, 0}, 5.0, 4);
        QVERIFY(std::abs(wrap.turnDegPerMm() - 5.0) < 1e-12);
        ShortTermMemory corner;
        corner.noteEdgeAt({0, 0}, 0.0, 4);
        corner.noteEdgeAt({0.5, 0}, 90.0, 4);
        const Decision capped = decide(p, corner, FollowingMode::Active, settings_, valid_);
        QVERIFY(distance(capped.follow,
                         settings_.followStep_mm * followDirection(37.0 + kMaxAnticipatedTurnDeg)) <
                1e-12);
        // A plane or air tap clears what the turn is estimated from.
        memory.update(region(Region::Air), false);
        QVERIFY(memory.recentEdges.empty());
        QCOMPARE(memory.turnDegPerMm(), 0.0);
    }

    void trustedOrientationSpan() {
        QVERIFY(orientationTrusted(edge(90, 4.0), valid_));
        QVERIFY(!orientationTrusted(edge(90, 4.5), valid_));
        QVERIFY(!orientationTrusted(region(Region::Plane), valid_));
    }
};

QTEST_APPLESS_MAIN(TestDecisionRules)
#include "test_decision_rules.moc"
