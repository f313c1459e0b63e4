// Objects as labs print them: a mesh file (binary STL, OBJ; in metres or millimetres) sliced by a
// horizontal plane into the outline the fingertip follows. The same extruded outline in every
// form slices to the same polygon; an open mesh, a slice above the object and files that are no
// mesh are refused by place.
#include <QTemporaryDir>
#include <QtTest>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "core/common/InputError.h"
#include "core/geometry/ShapeLibrary.h"
#include "core/scene/Scene.h"
#include "support/Refusals.h"

using namespace activetouch;

namespace {

using Point = std::array<double, 3>;
using Triangle = std::array<Point, 3>;

/// The cross outline extruded from z = 0 to `height`, outward-facing triangles: the caps fanned
/// from the centre (the cross is star-shaped about it), each side a quad of two triangles.
std::vector<Triangle> extruded(const std::vector<Vec2>& outline, double height, bool open) {
    std::vector<Triangle> t;
    const std::size_t n = outline.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = outline[i], b = outline[(i + 1) % n];
        t.push_back({Point{0, 0, 0}, Point{b.x, b.y, 0}, Point{a.x, a.y, 0}});
        t.push_back({Point{0, 0, height}, Point{a.x, a.y, height}, Point{b.x, b.y, height}});
        t.push_back({Point{a.x, a.y, 0}, Point{b.x, b.y, 0}, Point{b.x, b.y, height}});
        if (!(open && i == 3))
            t.push_back({Point{a.x, a.y, 0}, Point{b.x, b.y, height}, Point{a.x, a.y, height}});
    }
    return t;
}

void writeBinaryStl(const std::string& path, const std::vector<Triangle>& tris, double scale) {
    std::ofstream out(path, std::ios::binary);
    const char header[80] = "binary STL of an extruded cross";
    out.write(header, 80);
    const std::uint32_t count = static_cast<std::uint32_t>(tris.size());
    out.write(reinterpret_cast<const char*>(&count), 4);
    for (const Triangle& t : tris) {
        const float normal[3] = {0, 0, 0};
        out.write(reinterpret_cast<const char*>(normal), 12);
        for (const Point& p : t)
            for (double c : p) {
                const float f = static_cast<float>(c * scale);
                out.write(reinterpret_cast<const char*>(&f), 4);
            }
        const std::uint16_t attributes = 0;
        out.write(reinterpret_cast<const char*>(&attributes), 2);
    }
}

void writeObj(const std::string& path, const std::vector<Triangle>& tris, double scale) {
    std::ofstream out(path);
    out.precision(17);
    out << "# an extruded cross\n";
    for (const Triangle& t : tris)
        for (const Point& p : t)
            out << "v " << p[0] * scale << ' ' << p[1] * scale << ' ' << p[2] * scale << '\n';
    for (std::size_t i = 0; i < tris.size(); ++i)
        out << "f " << 3 * i + 1 << ' ' << 3 * i + 2 << ' ' << 3 * i + 3 << '\n';
}

void writeAsciiStl(const std::string& path, const std::vector<Triangle>& tris) {
    std::ofstream out(path);
    out.precision(17);
    out << "solid cross\n";
    for (const Triangle& t : tris) {
        out << "  facet normal 0 0 0\n    outer loop\n";
        for (const Point& p : t)
            out << "      vertex " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
        out << "    endloop\n  endfacet\n";
    }
    out << "endsolid cross\n";
}

/// An OBJ as CAD programs write it: faces naming vertices, texture and normal indices, counted
/// back from the last vertex ("f -3/1/1 -2/2/2 -1/3/3").
void writeObjRelative(const std::string& path, const std::vector<Triangle>& tris) {
    std::ofstream out(path);
    out.precision(17);
    out << "o cross\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n";
    for (const Triangle& t : tris) {
        for (const Point& p : t) out << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
        out << "f -3/1/1 -2/2/1 -1/3/1\n";
    }
}

/// The largest distance from a vertex of `a` to the nearest vertex of `b`.
double farthest(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    double worst = 0.0;
    for (const Vec2& p : a) {
        double best = 1e300;
        for (const Vec2& q : b) best = std::min(best, std::hypot(p.x - q.x, p.y - q.y));
        worst = std::max(worst, best);
    }
    return worst;
}

}  // namespace

class TestMeshObjects : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    std::vector<Vec2> cross_;

    ObjectSpec object(const std::string& json) {
        return parseObject(JsonFields(Json::parse(json), "lab.json", "/object"),
                           dir_.path().toStdString());
    }
    QString refusal(const std::string& json) {
        return test::refusalOf([&] { object(json); });
    }

private slots:
    void initTestCase() {
        QVERIFY(dir_.isValid());
        cross_ = libraryShape("cross", defaultShapeSize("cross")).vertices();
        const auto solid = extruded(cross_, 12.0, false);
        const std::string d = dir_.path().toStdString() + "/";
        writeBinaryStl(d + "cross_m.stl", solid, 0.001);
        writeBinaryStl(d + "cross_mm.stl", solid, 1.0);
        writeObj(d + "cross_m.obj", solid, 0.001);
        writeObj(d + "cross_mm.obj", solid, 1.0);
        writeBinaryStl(d + "open.stl", extruded(cross_, 12.0, true), 1.0);
        writeAsciiStl(d + "cross_ascii.stl", solid);
        writeObjRelative(d + "cross_relative.obj", solid);
        std::ofstream(d + "cross.ply") << "ply\nformat ascii 1.0\nend_header\n";
        std::ofstream(d + "notes.stl") << "these are notes, not a mesh\n";
    }

    void everyFormSlicesToTheSameOutline() {
        for (const auto& [file, units] : {std::pair{"cross_m.stl", "m"},
                                          {"cross_mm.stl", "mm"},
                                          {"cross_m.obj", "m"},
                                          {"cross_mm.obj", "mm"}}) {
            const ObjectSpec o =
                object(Json{{"shape", "mesh"}, {"file", file}, {"units", units}}.dump());
            QCOMPARE(o.shape, std::string("polygon"));
            QVERIFY2(std::abs(o.height_mm - 12.0) < 1e-4, file);  // the top comes from the mesh
            // The cross is centred on its bounding box already: the slice is its outline.
            QVERIFY2(farthest(o.polygon, cross_) < 0.01, file);
            QVERIFY2(farthest(cross_, o.polygon) < 0.01, file);
            QVERIFY2(std::abs(Polygon(o.polygon).area() - Polygon(cross_).area()) < 0.05, file);
        }
        // Any height of an extrusion gives the same outline.
        const ObjectSpec low = object(
            R"({"shape": "mesh", "file": "cross_mm.obj", "units": "mm", "slice_height_mm": 2})");
        QVERIFY(farthest(low.polygon, cross_) < 0.01);
    }

    void badMeshesAreRefusedByPlace() {
        const QString open = refusal(R"({"shape": "mesh", "file": "open.stl", "units": "mm"})");
        QVERIFY2(open.startsWith("/object/file") && open.contains("the mesh is open") &&
                     open.contains("belongs to one triangle only"),
                 qPrintable(open));
        const QString above = refusal(
            R"({"shape": "mesh", "file": "cross_mm.stl", "units": "mm", "slice_height_mm": 12.5})");
        QVERIFY2(above.startsWith("/object/slice_height_mm") &&
                     above.contains("outside the object") && above.contains("12 mm high"),
                 qPrintable(above));
        QVERIFY(
            refusal(R"({"shape": "mesh", "file": "cross_mm.stl"})").startsWith("/object/units"));
        QVERIFY(refusal(R"({"shape": "mesh", "file": "cross_mm.stl", "units": "furlong"})")
                    .contains("none of mm, cm, m, in"));
        const QString notes = refusal(R"({"shape": "mesh", "file": "notes.stl", "units": "mm"})");
        QVERIFY2(notes.startsWith("/object/file") && notes.contains("neither a binary STL"),
                 qPrintable(notes));
        QVERIFY(refusal(R"({"shape": "mesh", "file": "cross.ply", "units": "mm"})")
                    .contains("no .stl or .obj file"));
        QVERIFY(refusal(R"({"shape": "mesh", "file": "absent.stl", "units": "mm"})")
                    .contains("absent.stl"));
        QVERIFY(refusal(R"({"shape": "mesh", "file": ".", "units": "mm"})")
                    .contains("this is a folder"));
        QVERIFY(
            refusal(
                R"({"shape": "mesh", "file": "cross_mm.stl", "units": "mm", "top_height_mm": 5})")
                .startsWith("/object/top_height_mm"));
    }
};

QTEST_APPLESS_MAIN(TestMeshObjects)
#include "test_mesh_objects.moc"
