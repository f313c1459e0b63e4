// Drawings as labs make them: whole SVG documents (viewBox and physical size, nested transforms,
// basic shapes) read into the outline of one element, in mm. Each outline is checked against the
// transforms computed here independently; units in px and inches are converted as SVG
// specifies (96 px to the inch); bad documents are refused naming the element and its line.
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <fstream>

#include "core/common/InputError.h"
#include "core/geometry/Polygon.h"
#include "core/scene/Scene.h"
#include "core/scene/SvgObject.h"
#include "core/test_svg_drawings.h"  // the documents read here
#include "support/Refusals.h"

using namespace activetouch;

namespace {

/// Where SVG puts (x, y) of the group: rotate(30) after translate(10 5), in mm (the viewBox maps
/// a user unit to a millimetre).
Vec2 drawn(double x, double y) {
    const double a = 30.0 * M_PI / 180.0, u = x + 10.0, v = y + 5.0;
    return {std::cos(a) * u - std::sin(a) * v, std::sin(a) * u + std::cos(a) * v};
}

/// `points` as the object keeps an outline: y up, centred on their bounding box.
std::vector<Vec2> upright(const std::vector<Vec2>& points) {
    Vec2 lo = points.front(), hi = lo;
    for (const Vec2& p : points) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const Vec2 c = 0.5 * (lo + hi);
    std::vector<Vec2> out;
    for (const Vec2& p : points) out.push_back({p.x - c.x, c.y - p.y});
    return out;
}

double nearest(const std::vector<Vec2>& among, Vec2 p) {
    double best = 1e300;
    for (const Vec2& q : among) best = std::min(best, std::hypot(p.x - q.x, p.y - q.y));
    return best;
}

}  // namespace

class TestSvgDocuments : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;

    void write(const char* name, const std::string& text) {
        std::ofstream(dir_.filePath(name).toStdString()) << text;
    }
    SvgFileOutline read(const Json& object) {
        return svgFileOutline(JsonFields(object, "lab.json", "/object"), dir_.path().toStdString());
    }
    QString refusal(const Json& object) {
        return test::refusalOf([&] { read(object); });
    }

private slots:
    void initTestCase() {
        QVERIFY(dir_.isValid());
        write("drawing.svg", kDrawing);
    }

    void eachElementComesOutWhereItsTransformsPutIt() {
        // The triangle: its three corners, exactly.
        const SvgFileOutline p = read({{"file", "drawing.svg"}, {"element", "p"}});
        const auto expected = upright({drawn(0, 0), drawn(10, 0), drawn(10, 10)});
        QCOMPARE(p.outline.size(), std::size_t(3));
        for (const Vec2& v : expected) QVERIFY(nearest(p.outline, v) < 0.01);
        QVERIFY(QString::fromStdString(p.element).contains("path 'p' (line 7)"));
        // The circle: every vertex 10 mm from its centre (within the flattening tolerance).
        const SvgFileOutline c = read({{"file", "drawing.svg"}, {"element", "c"}});
        for (const Vec2& v : c.outline) QVERIFY(std::abs(std::hypot(v.x, v.y) - 10.0) < 0.06);
        // The rounded rectangle: its area less the corners' (4 - pi) rx^2, and its corners' arcs
        // tangent to the sides where the transform puts them.
        const SvgFileOutline r = read({{"file", "drawing.svg"}, {"element", "r"}});
        // (Flattened within 0.05 mm, the corners' chords lose at most their length times that.)
        QVERIFY(std::abs(Polygon(r.outline).area() - (200.0 - (4.0 - M_PI) * 4.0)) <
                2.0 * M_PI * 2.0 * 0.05);
        const auto sides = upright({drawn(10, 10), drawn(30, 10), drawn(30, 20), drawn(10, 20)});
        const auto tangents = upright({drawn(10, 10), drawn(30, 10), drawn(30, 20), drawn(10, 20),
                                       drawn(12, 10), drawn(28, 20)});
        QVERIFY(nearest(r.outline, tangents[4]) < 0.01);
        QVERIFY(nearest(r.outline, tangents[5]) < 0.01);
        QVERIFY(nearest(r.outline, sides[0]) > 0.5);  // the corner itself is rounded off
    }

    void withoutAnIdTheLargestClosedOutlineIsFollowedAndTheRestNamed() {
        const SvgFileOutline any = read({{"file", "drawing.svg"}});
        QVERIFY(QString::fromStdString(any.element).startsWith("circle 'c'"));
        QCOMPARE(any.others.size(), std::size_t(2));  // the rectangle and the triangle
        QVERIFY(QString::fromStdString(any.others[0]).startsWith("rect 'r'"));
    }

    void aDrawingProgramsFileIsRead() {
        // Inkscape's own elements and attributes, a title and text beside the drawing.
        write("inkscape.svg", kInkscape);
        const SvgFileOutline plate = read({{"file", "inkscape.svg"}});
        QVERIFY2(QString::fromStdString(plate.element).startsWith("rect 'plate' (line"),
                 plate.element.c_str());
        QVERIFY(std::abs(Polygon(plate.outline).area() - (1500.0 - (4.0 - M_PI) * 16.0)) <
                2.0 * M_PI * 4.0 * 0.05);
    }

    void pixelsAndInchesAreConvertedAsSvgSpecifies() {
        write("px.svg", kPixels);
        QVERIFY(std::abs(Polygon(read({{"file", "px.svg"}}).outline).area() - 0.5 * 25.4 * 12.7) <
                1e-6);
        write("in.svg", kInches);
        QVERIFY(std::abs(Polygon(read({{"file", "in.svg"}}).outline).area() - 50.8 * 25.4) < 1e-6);
    }

    void badDocumentsAreRefusedByElementAndLine() {
        QVERIFY(refusal({{"file", "drawing.svg"}, {"element", "nothere"}})
                    .contains("no element with id 'nothere'; its ids: c, r, p, open"));
        const QString open = refusal({{"file", "drawing.svg"}, {"element", "open"}});
        QVERIFY2(open.startsWith("/object/element") && open.contains("polyline 'open' (line 8)") &&
                     open.contains("no closed outline"),
                 qPrintable(open));
        write("bad.svg", kBadPath);
        const QString bad = refusal({{"file", "bad.svg"}});
        QVERIFY2(bad.startsWith("/object/file") && bad.contains("at the path 'bad' (line 4)") &&
                     bad.contains("\"d\""),
                 qPrintable(bad));
        write("notxml.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path d=\"M0 0\"\n");
        QVERIFY(refusal({{"file", "notxml.svg"}}).contains("is not XML (line"));
        write("html.svg", "<html><body/></html>");
        QVERIFY(refusal({{"file", "html.svg"}}).contains("no SVG document"));
        QVERIFY(refusal({{"file", "absent.svg"}}).contains("absent.svg"));
    }

    void aSceneFollowsADrawing() {
        const ObjectSpec o = parseObject(
            JsonFields(Json{{"shape", "svg_file"}, {"file", "drawing.svg"}, {"element", "p"}},
                       "lab.json", "/object"),
            dir_.path().toStdString());
        QCOMPARE(o.shape, std::string("polygon"));
        QCOMPARE(o.polygon.size(), std::size_t(3));
    }
};

QTEST_APPLESS_MAIN(TestSvgDocuments)
#include "test_svg_documents.moc"
