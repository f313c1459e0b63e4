// Outlines from SVG path data (core/geometry/SvgPath.h): every command, absolute and relative,
// flattened within the tolerance asked for; degenerate and hostile path data refused by place.
#include <QtTest>
#include <cmath>
#include <functional>

#include "core/common/InputError.h"
#include "core/geometry/SvgPath.h"

using namespace activetouch;

namespace {
Polygon parse(const std::string& d, double tolerance = 0.05) {
    return polygonFromSvgPath(d, tolerance, "shape.svg", "/path");
}

/// The distance from `p` to the polygon's outline.
double distanceToOutline(const Polygon& poly, Vec2 p) {
    double best = 1e300;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly.vertex(i), b = poly.vertex(i + 1), ab = b - a;
        const double len2 = ab.x * ab.x + ab.y * ab.y;
        const double t =
            len2 > 0 ? std::clamp(((p.x - a.x) * ab.x + (p.y - a.y) * ab.y) / len2, 0.0, 1.0) : 0.0;
        const Vec2 q = a + t * ab;
        best = std::min(best, std::hypot(p.x - q.x, p.y - q.y));
    }
    return best;
}

/// The largest distance from the true curve `at(t)`, t in [0, 1], to the outline.
double deviation(const Polygon& poly, const std::function<Vec2(double)>& at) {
    double worst = 0.0;
    for (int i = 0; i <= 2000; ++i)
        worst = std::max(worst, distanceToOutline(poly, at(i / 2000.0)));
    return worst;
}

Vec2 cubicAt(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3, double t) {
    const double u = 1 - t;
    return u * u * u * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t * t * t * p3;
}

/// The refusal `d` gets: its place and problem.
QString refusal(const std::string& d, double tolerance = 0.05) {
    try {
        parse(d, tolerance);
    } catch (const InputError& e) {
        return QString::fromStdString(e.place() + " | " + e.problem());
    }
    return {};
}
}  // namespace

class TestSvgPath : public QObject {
    Q_OBJECT
private slots:
    void linesAbsoluteAndRelativeDrawTheSameSquare() {
        const std::vector<Vec2> square{{0, 0}, {20, 0}, {20, 10}, {0, 10}};
        for (const std::string d :
             {"M0 0 L20 0 L20 10 L0 10 Z", "M 0,0 H 20 V 10 H 0 Z", "m0 0 l20 0 0 10 -20 0 z",
              "M0 0 h20 v10 h-20 z", "M0,0 20,0 20,10 0,10Z", "M0 0L20 0L20 10L0 10L0 0"}) {
            const Polygon p = parse(d);
            QCOMPARE(p.size(), std::size_t(4));
            QVERIFY2(std::abs(p.area() - 200.0) < 1e-9, d.c_str());
            for (const Vec2& v : square) QVERIFY2(distanceToOutline(p, v) < 1e-12, d.c_str());
        }
    }

    void numbersReadAsSvgWritesThem() {
        // No separators between a number and a sign, ".5.5" as two numbers, exponents.
        const Polygon p = parse("M0,0L1e1-0 10,5.5.5,10-5e-1-.5z");
        QCOMPARE(p.size(), std::size_t(5));
        QVERIFY(distanceToOutline(p, {10, 0}) < 1e-12);
        QVERIFY(distanceToOutline(p, {10, 5.5}) < 1e-12);
        QVERIFY(distanceToOutline(p, {0.5, 10}) < 1e-12);
        QVERIFY(distanceToOutline(p, {-0.5, -0.5}) < 1e-12);
    }

    void cubicsStayWithinTheTolerance() {
        // A lens of two cubics, then the same drawn with S (the reflected control point).
        for (const double tol : {0.5, 0.05, 0.01}) {
            const Polygon lens = parse("M0 0 C10 -10 20 -10 30 0 C20 10 10 10 0 0 Z", tol);
            const double worst =
                std::max(deviation(lens,
                                   [](double t) {
                                       return cubicAt({0, 0}, {10, -10}, {20, -10}, {30, 0}, t);
                                   }),
                         deviation(lens, [](double t) {
                             return cubicAt({30, 0}, {20, 10}, {10, 10}, {0, 0}, t);
                         }));
            QVERIFY2(worst <= tol + 1e-9, qPrintable(QString("%1 > %2").arg(worst).arg(tol)));
            // Finer tolerance, more vertices.
            if (tol == 0.01)
                QVERIFY(lens.size() >
                        parse("M0 0 C10 -10 20 -10 30 0 C20 10 10 10 0 0 Z", 0.5).size());
        }
        const Polygon smooth = parse("M0 0 C0 -10 30 -10 30 0 S0 10 0 0 Z");
        QVERIFY(deviation(smooth, [](double t) {
                    return cubicAt({30, 0}, {30, 10}, {0, 10}, {0, 0}, t);
                }) <= 0.05 + 1e-9);
        const Polygon relative = parse("m0 0 c10 -10 20 -10 30 0 s-20 10 -30 0 z");
        QVERIFY(std::abs(relative.area() - parse("M0 0 C10 -10 20 -10 30 0 S10 10 0 0 Z").area()) <
                1e-9);
    }

    void quadraticsStayWithinTheTolerance() {
        // Q then T: T's control point is Q's reflected through the point between them.
        const Polygon q = parse("M0 0 Q15 -15 30 0 T0 0 Z");
        auto quadAt = [](Vec2 a, Vec2 c, Vec2 b, double t) {
            const double u = 1 - t;
            return u * u * a + 2 * u * t * c + t * t * b;
        };
        QVERIFY(deviation(q, [&](double t) {
                    return quadAt({0, 0}, {15, -15}, {30, 0}, t);
                }) <= 0.05 + 1e-9);
        QVERIFY(deviation(q, [&](double t) {
                    return quadAt({30, 0}, {45, 15}, {0, 0}, t);
                }) <= 0.05 + 1e-9);
        QVERIFY(std::abs(q.area() - parse("m0 0 q15 -15 30 0 t-30 0 z").area()) < 1e-9);
    }

    void arcsDrawCirclesAndEllipses() {
        // A circle of radius 15 as two half arcs: every vertex on it, the area within the
        // tolerance's share of pi r^2.
        for (const double tol : {0.1, 0.01}) {
            const Polygon c = parse("M-15 0 A15 15 0 0 1 15 0 A15 15 0 0 1 -15 0 Z", tol);
            for (const Vec2& v : c.vertices())
                QVERIFY(std::abs(std::hypot(v.x, v.y) - 15.0) < 1e-9);
            QVERIFY(deviation(c, [](double t) {
                        return Vec2{15 * std::cos(2 * M_PI * t), 15 * std::sin(2 * M_PI * t)};
                    }) <= tol + 1e-9);
            QVERIFY(std::abs(c.area() - M_PI * 225) < 2 * M_PI * 15 * tol);
        }
        // A rotated ellipse (30 degrees), relative: each vertex satisfies its equation.
        const Polygon e = parse("M-20 0 a20 10 0 0 1 40 0 a20 10 0 0 1 -40 0 z");
        for (const Vec2& v : e.vertices())
            QVERIFY(std::abs(v.x * v.x / 400 + v.y * v.y / 100 - 1) < 1e-9);
        const Polygon turned = parse("M0 0 A20 10 30 1 1 1 0 Z");
        QVERIFY(turned.area() > 0);
        // Radii too small to reach are scaled up: a half circle through both ends.
        const Polygon grown = parse("M0 0 A1 1 0 0 1 20 0 Z");
        // (The flattened arc lies inside the curve, short of it by at most the tolerance.)
        QVERIFY2(std::abs(grown.area() - 0.5 * M_PI * 100) < M_PI * 10 * 0.05,
                 qPrintable(QString::number(grown.area())));
        // Flags written without separators.
        QVERIFY(parse("M0 0A10 10 0 0120 0Z").area() > 100);
    }

    void arcsOfExtremeRadiiAreTheArcsSvgSpecifies() {
        // Radii far below or above the endpoints' distance are scaled (or kept) as SVG says at
        // every scale: never a chord where an arc is specified. From (0,40) to (40,40), sweep 1,
        // radii too small to reach: the half circle of radius 20 about (20,40), below the chord
        // (y down in SVG's sense of sweep: the positive-angle direction).
        for (const double r : {1e-12, 1e-154, 1e-155, 1e-200, 1e-300, 4.9e-324}) {
            const std::string d = "M 0,40 A " + QByteArray::number(r, 'g', 17).toStdString() + " " +
                                  QByteArray::number(r, 'g', 17).toStdString() + " 0 0 1 40 40 Z";
            const Polygon half = parse(d);
            QVERIFY2(half.size() > 20, d.c_str());
            for (const Vec2& v : half.vertices())
                QVERIFY2(std::abs(std::hypot(v.x - 20, v.y - 40) - 20) < 1e-9, d.c_str());
            QVERIFY2(std::abs(half.area() - 0.5 * M_PI * 400) < M_PI * 20 * 0.05, d.c_str());
            QVERIFY2(
                deviation(
                    half,
                    [](double t) {
                        return Vec2{20 - 20 * std::cos(M_PI * t), 40 - 20 * std::sin(M_PI * t)};
                    }) <= 0.05 + 1e-9,
                d.c_str());
        }
        // An ellipse of aspect 2 at a tiny scale grows with its aspect kept: half an ellipse of
        // radii 20 and 40 through both ends.
        const Polygon tall = parse("M 0,0 A 1e-250 2e-250 0 0 1 40 0 Z");
        QVERIFY(tall.size() > 20);
        for (const Vec2& v : tall.vertices())
            QVERIFY(std::abs(std::pow((v.x - 20) / 20, 2) + std::pow(v.y / 40, 2) - 1) < 1e-9);
        QVERIFY(std::abs(tall.area() - 0.5 * M_PI * 20 * 40) < M_PI * 40 * 0.05);
        // Huge radii that already reach are kept: beyond the coordinate bound they are refused,
        // not silently drawn as a chord.
        QVERIFY_THROWS_EXCEPTION(InputError, parse("M 0,40 A 1e300 1e300 0 0 1 40 40 Z"));
        // A flatness past doubles along the chord is the chord, as the flat ellipse is.
        const Polygon flat = parse("M 0,0 A 1000 4.9e-324 0 0 1 40 0 L 20 20 Z");
        QCOMPARE(flat.size(), std::size_t(3));
    }

    void aMoveAfterAMoveStartsTheOutlineThere() {
        // SVG: a second moveto before anything is drawn moves the start; "m" after "M" is
        // relative to the first point, and its further pairs are relative lines.
        const Polygon p = parse("M 40,40 m -6,-4 l 20,0 0,10 -20,0 z");
        QCOMPARE(p.size(), std::size_t(4));
        for (const Vec2 v : std::vector<Vec2>{{34, 36}, {54, 36}, {54, 46}, {34, 46}})
            QVERIFY(distanceToOutline(p, v) < 1e-12);
        QCOMPARE(parse("M0 0 M5 5 L15 5 L15 15 Z").area(), 50.0);
        QVERIFY(refusal("M0 0 L10 0 M20 20 L30 30 Z").contains("a second move"));
    }

    void everyCommandRepeatsOverItsParameterGroups() {
        // Each command letter takes as many parameter groups as follow it; a moveto's further
        // pairs are linetos (absolute after M, relative after m).
        struct Case {
            std::string repeated, spelled;
        };
        const QList<Case> cases{
            {"M0 0 10 0 10 10 0 10 Z", "M0 0 L10 0 L10 10 L0 10 Z"},
            {"m0 0 10 0 0 10 -10 0 z", "M0 0 l10 0 l0 10 l-10 0 z"},
            {"M0 0 L10 0 10 10 0 10 Z", "M0 0 L10 0 L10 10 L0 10 Z"},
            {"M0 0 l10 0 0 10 -10 0 z", "M0 0 l10 0 l0 10 l-10 0 z"},
            {"M0 0 H10 20 V10 20 H0 Z", "M0 0 H10 H20 V10 V20 H0 Z"},
            {"M0 0 h10 10 v10 10 h-20 z", "M0 0 h10 h10 v10 v10 h-20 z"},
            {"M0 0 C0 5 5 10 10 10 15 10 20 5 20 0 Z", "M0 0 C0 5 5 10 10 10 C15 10 20 5 20 0 Z"},
            {"M0 0 c0 5 5 10 10 10 5 0 10 -5 10 -10 z", "M0 0 c0 5 5 10 10 10 c5 0 10 -5 10 -10 z"},
            {"M0 0 C0 5 5 10 10 10 S20 5 20 0 30 -5 30 0 V-30 H0 Z",
             "M0 0 C0 5 5 10 10 10 S20 5 20 0 S30 -5 30 0 V-30 H0 Z"},
            {"M0 0 Q5 10 10 0 15 -10 20 0 V-30 H0 Z", "M0 0 Q5 10 10 0 Q15 -10 20 0 V-30 H0 Z"},
            {"M0 0 Q5 10 10 0 T20 0 30 0 V-30 H0 Z", "M0 0 Q5 10 10 0 T20 0 T30 0 V-30 H0 Z"},
            {"M0 0 q5 10 10 0 t10 0 10 0 v-30 h-30 z", "M0 0 q5 10 10 0 t10 0 t10 0 v-30 h-30 z"},
            {"M0 0 A5 5 0 0 1 10 0 5 5 0 0 1 0 0 Z", "M0 0 A5 5 0 0 1 10 0 A5 5 0 0 1 0 0 Z"},
            {"M0 0 a5 5 0 0 1 10 0 5 5 0 0 1 -10 0 z", "M0 0 a5 5 0 0 1 10 0 a5 5 0 0 1 -10 0 z"},
        };
        for (const Case& c : cases) {
            const Polygon a = parse(c.repeated), b = parse(c.spelled);
            QVERIFY2(a.size() == b.size(), c.repeated.c_str());
            for (std::size_t i = 0; i < a.size(); ++i)
                QVERIFY2(std::hypot(a.vertex(i).x - b.vertex(i).x, a.vertex(i).y - b.vertex(i).y) <
                             1e-12,
                         c.repeated.c_str());
        }
    }

    void badPathDataIsRefusedByPlace() {
        struct Case {
            std::string d;
            QString place, problem;
        };
        const QList<Case> cases{
            {"M0 0 L10 0 X5 5 Z", "character 12", "unknown command 'X'"},
            {"M0 0 L10", "(command L)", "a number is missing"},
            {"M0 0 L10 0 L10 abc Z", "character 16", "expected a number"},
            {"M0 0 Lnan 0 L0 5 Z", "(command L)", "expected a number"},
            {"M0 0 L1e9 0 L0 5 Z", "(command L)", "beyond what an outline on the stage can use"},
            {"M0 0 L10 0 L10 10", "/path", "does not close"},
            {"M0 0 L10 0 L10 10 Z M20 20 L30 20 L30 30 Z", "(command M)",
             "a second outline after Z"},
            {"M0 0 L10 0 M20 20 L30 30 Z", "(command M)", "a second move"},
            {"L10 0 L10 10 Z", "(command L)", "must begin with a move"},
            {"M0 0 L10 10 L10 0 L0 10 Z", "/path", "cannot be an object"},  // a bow tie
            {"M0 0 L10 0 L0 0 Z", "/path", "cannot be an object"},          // no area
            {"M5 5 Z", "/path", "cannot be an object"},                     // no length
            {"", "/path", "empty"},
            {"M0 0 A5 5 0 2 1 10 0 Z", "(command A)", "arc flag must be 0 or 1"},
            {"M0 0 L10 0 L10 10 Z 5", "(command Z)", "Z takes no numbers"},
        };
        for (const Case& c : cases) {
            const QString message = refusal(c.d);
            QVERIFY2(message.contains(c.place) && message.contains(c.problem),
                     qPrintable(QString::fromStdString(c.d) + " -> " + message));
            QVERIFY(message.startsWith("/path"));
        }
        QVERIFY(refusal("M0 0 L10 0 L10 10 Z", 0.0).contains("tolerance"));
        QVERIFY(refusal("M0 0 L10 0 L10 10 Z", std::nan("")).contains("tolerance"));
        // Hostile bytes: a NUL, control characters, a huge run of digits.
        QVERIFY(!refusal(std::string("M0 0 L10 0\0L5 5 Z", 17)).isEmpty());
        QVERIFY(refusal("M0 0 L10 0 L5 " + std::string(5000, '9') + " Z").contains("beyond"));
        // A needle of an ellipse: its radii, grown to reach the end point, would run to 1e20 mm.
        QVERIFY(refusal("M0 0 A1 1e-17 0 1 1 0 5000 Z").contains("arc's radii, grown"));
        QVERIFY(refusal("M0 0 A1 1e-17 0 1 1 0 5000 Z").contains("(command A)"));
        // A wide, shallow arc at a fine tolerance is still drawn.
        QVERIFY(std::abs(parse("M0 0 A9999 9999 0 0 1 10 0 L10 10 Z", 1e-9).area() - 50.0) < 0.01);
        // A tolerance too fine for the path: refused, not ten thousand vertices and more.
        QVERIFY(refusal("M-9000 0 A9000 9000 0 0 1 9000 0 A9000 9000 0 0 1 -9000 0 Z", 1e-6)
                    .contains("more than 10000 vertices"));
    }
};

QTEST_APPLESS_MAIN(TestSvgPath)
#include "test_svg_path.moc"
