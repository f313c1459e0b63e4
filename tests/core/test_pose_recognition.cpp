// Recognition at any pose: every library shape, traced with noise from any start point, turned by
// random angles and moved, is named right with its turn (modulo its symmetry) and place; sizes
// count; degenerate paths get no name and no NaN.
#include <QtTest>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "core/geometry/ShapeLibrary.h"
#include "core/recognition/PoseGrid.h"
#include "core/recognition/PoseRecognition.h"

using namespace activetouch;

namespace {

std::vector<PoseTemplate> libraryTemplates() {
    std::vector<PoseTemplate> t;
    for (const auto& n : libraryShapeNames())
        t.push_back(poseTemplate(n, libraryShape(n, defaultShapeSize(n)), 0.0));
    return t;
}

/// Taps every `step` mm along `outline` from `startArc`, once round, each off by Gaussian noise.
std::vector<Vec2> tracedPath(const Polygon& outline, double step, double startArc, double noise,
                             std::mt19937& rng) {
    std::normal_distribution<double> jitter(0.0, noise);
    std::vector<Vec2> path;
    for (double s = 0.0; s <= outline.perimeter(); s += step) {
        const Vec2 p = outline.pointAtArcLength(startArc + s);
        path.push_back(p + Vec2{jitter(rng), jitter(rng)});
    }
    return path;
}

}  // namespace

class TestPoseRecognition : public QObject {
    Q_OBJECT
private slots:
    void everyShapeAtRandomPosesIsNamedWithItsTurnAndPlace_data() {
        QTest::addColumn<QString>("shape");
        for (const auto& n : libraryShapeNames())
            QTest::newRow(n.c_str()) << QString::fromStdString(n);
    }
    void everyShapeAtRandomPosesIsNamedWithItsTurnAndPlace() {
        QFETCH(QString, shape);
        static const std::vector<PoseTemplate> templates = libraryTemplates();
        const std::string name = shape.toStdString();
        const Polygon own = libraryShape(name, defaultShapeSize(name));
        std::mt19937 rng(std::hash<std::string>{}(name)&0xffff);
        std::uniform_real_distribution<double> turnOf(0.0, 360.0), placeOf(60.0, 240.0),
            startOf(0.0, 1.0);
        for (int k = 0; k < 10; ++k) {
            const double turn = turnOf(rng);
            const Vec2 place{placeOf(rng), placeOf(rng)};
            const Polygon placed = own.transformed(turn, place);
            // The truth: where the outline's centroid went.
            const PoseTemplate* tpl = nullptr;
            for (const auto& t : templates)
                if (t.shape == name) tpl = &t;
            const double a = turn * M_PI / 180.0;
            const Vec2 centre =
                place + Vec2{std::cos(a) * tpl->centroid.x - std::sin(a) * tpl->centroid.y,
                             std::sin(a) * tpl->centroid.x + std::cos(a) * tpl->centroid.y};
            const auto path = tracedPath(placed, 2.0, startOf(rng) * placed.perimeter(), 0.5, rng);
            const PoseRecognition r = recognisePose(path, templates);
            QVERIFY(r.valid);
            QVERIFY2(r.predicted == name,
                     qPrintable(QString("turned %1: named %2")
                                    .arg(turn)
                                    .arg(QString::fromStdString(r.predicted))));
            QCOMPARE(r.fits.size(), templates.size());  // every template scored
            if (r.best.symmetry != 0) {
                const double err = rotationErrorDeg(r.best.rotationDeg, turn, r.best.symmetry);
                QVERIFY2(err <= 3.0, qPrintable(QString("turned %1, recovered %2 (symmetry %3)")
                                                    .arg(turn)
                                                    .arg(r.best.rotationDeg)
                                                    .arg(r.best.symmetry)));
            }
            QVERIFY2(distance(r.best.position, centre) <= 1.0,
                     qPrintable(QString("centred at (%1, %2), recovered (%3, %4)")
                                    .arg(centre.x)
                                    .arg(centre.y)
                                    .arg(r.best.position.x)
                                    .arg(r.best.position.y)));
            for (const PoseFit& f : r.fits) QVERIFY(std::isfinite(f.score_mm));
        }
    }

    void symmetriesAreFound() {
        const auto t = libraryTemplates();
        auto symmetryOf = [&](const std::string& n) {
            for (const auto& x : t)
                if (x.shape == n) return x.symmetry;
            return -1;
        };
        QCOMPARE(symmetryOf("rectangle"), 2);
        QCOMPARE(symmetryOf("cross"), 4);
        QCOMPARE(symmetryOf("triangle"), 3);
        QCOMPARE(symmetryOf("star"), 5);
        QCOMPARE(symmetryOf("gear"), 6);
        QCOMPARE(symmetryOf("circle"), 0);
        QCOMPARE(symmetryOf("L"), 1);
        QCOMPARE(symmetryOf("heart"), 1);
        // The turn of a symmetric shape is judged modulo its symmetry.
        QCOMPARE(rotationErrorDeg(179.0, 1.0, 2), 2.0);
        QCOMPARE(rotationErrorDeg(359.0, 1.0, 1), 2.0);
        QCOMPARE(rotationErrorDeg(123.0, 7.0, 0), 0.0);
    }

    void sizeCountsAsItsOwn() {
        // Circles of 30 and 60 mm are different shapes: a path round either is named by size.
        std::vector<PoseTemplate> t{
            poseTemplate("small", libraryShape("circle", {30, 30, 0, 0}), 0),
            poseTemplate("large", libraryShape("circle", {60, 60, 0, 0}), 0)};
        std::mt19937 rng(7);
        QCOMPARE(recognisePose(
                     tracedPath(libraryShape("circle", {30, 30, 0, 0}).transformed(0, {100, 100}),
                                2, 0, 0.3, rng),
                     t)
                     .predicted,
                 std::string("small"));
        QCOMPARE(recognisePose(
                     tracedPath(libraryShape("circle", {60, 60, 0, 0}).transformed(0, {100, 100}),
                                2, 0, 0.3, rng),
                     t)
                     .predicted,
                 std::string("large"));
    }

    void aPathAlongPartOfAnOutlineDoesNotFitTheWhole() {
        // Half of the rectangle's outline is not the rectangle's whole: the two-way score is
        // worse than for the whole path.
        const auto t = libraryTemplates();
        const Polygon r =
            libraryShape("rectangle", defaultShapeSize("rectangle")).transformed(30, {150, 150});
        std::mt19937 rng(3);
        auto whole = tracedPath(r, 2, 0, 0.3, rng);
        std::vector<Vec2> half(whole.begin(), whole.begin() + static_cast<long>(whole.size() / 2));
        auto scoreOf = [&](const PoseRecognition& p) {
            for (const auto& f : p.fits)
                if (f.shape == "rectangle") return f.score_mm;
            return -1.0;
        };
        QVERIFY(scoreOf(recognisePose(half, t)) > scoreOf(recognisePose(whole, t)) + 1.0);
    }

    void vectorAndPortableReadingsGiveTheSameFits() {
        // Templates of every library shape, on the outline and offset outward, and paths at
        // random poses: whole, part of an outline, overshooting, of every length modulo four,
        // and far outside every grid. Grids, names, scores, turns and places agree bit for bit.
        const auto same = [](double a, double b) {
            return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
        };
        std::vector<PoseTemplate> vector, portable;
        for (const double offset : {0.0, 3.0})
            for (const auto& n : libraryShapeNames()) {
                const Polygon own = libraryShape(n, defaultShapeSize(n));
                vector.push_back(detail::poseTemplate(n, own, offset, false));
                portable.push_back(detail::poseTemplate(n, own, offset, true));
                const PoseTemplate &v = vector.back(), &p = portable.back();
                QCOMPARE(v.nx, p.nx);
                QCOMPARE(v.ny, p.ny);
                QCOMPARE(v.symmetry, p.symmetry);
                QVERIFY(v.distance == p.distance);
            }
        std::mt19937 rng(91);
        std::uniform_real_distribution<double> turnOf(0.0, 360.0), placeOf(60.0, 240.0),
            unit(0.0, 1.0);
        std::vector<std::vector<Vec2>> paths;
        for (const auto& n : libraryShapeNames()) {
            const Polygon placed = libraryShape(n, defaultShapeSize(n))
                                       .transformed(turnOf(rng), {placeOf(rng), placeOf(rng)});
            auto path = tracedPath(placed, 2.0, unit(rng) * placed.perimeter(), 0.5, rng);
            paths.push_back(path);
            paths.emplace_back(path.begin(), path.begin() + static_cast<long>(path.size() / 3));
            path[path.size() / 2] = path[path.size() / 2] + Vec2{8.0, -6.0};  // an overshoot
            paths.push_back(path);
        }
        for (std::size_t n = 3; n <= 8; ++n) {
            std::vector<Vec2> shortPath;
            for (std::size_t i = 0; i < n; ++i)
                shortPath.push_back({100.0 + 3.0 * double(i), 100.0 + double(i * i) * 0.5});
            paths.push_back(shortPath);
        }
        paths.push_back({{1e6, 1e6}, {1e6 + 1, 1e6}, {1e6, 1e6 + 1}, {1e6 + 2, 1e6 + 3}, {1e6, 3}});
        for (const auto& path : paths) {
            const PoseRecognition v = detail::recognisePose(path, vector, false);
            const PoseRecognition p = detail::recognisePose(path, portable, true);
            QCOMPARE(v.valid, p.valid);
            QCOMPARE(v.predicted, p.predicted);
            QCOMPARE(v.fits.size(), p.fits.size());
            for (std::size_t i = 0; i < v.fits.size(); ++i) {
                QVERIFY(same(v.fits[i].score_mm, p.fits[i].score_mm));
                QVERIFY(same(v.fits[i].rotationDeg, p.fits[i].rotationDeg));
                QVERIFY(same(v.fits[i].position.x, p.fits[i].position.x));
                QVERIFY(same(v.fits[i].position.y, p.fits[i].position.y));
            }
        }
    }

    void aCostStopsOnlyOnceItReachesItsLimit() {
        // The search asks a cost with a limit: at or above it the answer is +infinity, below it
        // the very bits of the cost asked without one, whatever the point count modulo the runs
        // the sum is read in, with vector and portable readings alike.
        const auto same = [](double a, double b) {
            return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
        };
        const Polygon c = libraryShape("C", defaultShapeSize("C"));
        std::mt19937 rng(7);
        for (const bool portable : {false, true}) {
            const PoseTemplate tpl = detail::poseTemplate("C", c, 0.0, portable);
            const posegrid::Grid grid = posegrid::gridOf(tpl, portable);
            for (const std::size_t n : {1u, 5u, 31u, 32u, 33u, 70u, 131u}) {
                auto path = tracedPath(c.transformed(3.0, {-2.0, 1.5}), 1.0, 0.0, 0.8, rng);
                path.resize(std::min(n, path.size()));
                const posegrid::Coords points(path);
                const posegrid::Pose pose{4.0, {1.0, -0.5}};
                const double whole = posegrid::meanCost(
                    grid, points, pose, posegrid::Mapping::IntoFrame, posegrid::Lookup::Bilinear);
                QVERIFY(whole > 0.0 && std::isfinite(whole));
                for (const double before : {0.0, 0.3}) {
                    const auto bounded = [&](double limit) {
                        return posegrid::meanCost(grid, points, pose, posegrid::Mapping::IntoFrame,
                                                  posegrid::Lookup::Bilinear, before, limit);
                    };
                    QVERIFY(same(bounded(before + whole * 1.001), whole));
                    QVERIFY(same(bounded(std::numeric_limits<double>::infinity()), whole));
                    QCOMPARE(bounded(before + whole), std::numeric_limits<double>::infinity());
                    QCOMPARE(bounded(before + whole * 0.25),
                             std::numeric_limits<double>::infinity());
                }
            }
        }
    }

    void degeneratePathsGetNoNameAndNoNaN() {
        const auto t = libraryTemplates();
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const double inf = std::numeric_limits<double>::infinity();
        QVERIFY(!recognisePose({}, t).valid);
        QVERIFY(!recognisePose({{1, 1}, {2, 2}}, t).valid);
        QVERIFY(!recognisePose({{nan, 1}, {2, inf}, {3, 3}}, t).valid);
        QVERIFY(!recognisePose({{0, 0}, {10, 0}, {20, 0}}, {}).valid);  // no template
        // All points on one spot, or on a line: a name, finite scores, no crash.
        for (const auto& path : {std::vector<Vec2>(50, Vec2{150, 150}),
                                 std::vector<Vec2>{{0, 0}, {10, 0}, {20, 0}, {30, 0}},
                                 std::vector<Vec2>{{1e6, 1e6}, {1e6 + 1, 1e6}, {1e6, 1e6 + 1}}}) {
            const PoseRecognition r = recognisePose(path, t);
            for (const PoseFit& f : r.fits) {
                QVERIFY(std::isfinite(f.score_mm));
                QVERIFY(std::isfinite(f.rotationDeg));
                QVERIFY(std::isfinite(f.position.x) && std::isfinite(f.position.y));
            }
        }
    }
};

QTEST_APPLESS_MAIN(TestPoseRecognition)
#include "test_pose_recognition.moc"
