#include "core/scene/MeshObject.h"

#include <algorithm>
#include <cmath>

#include "core/common/InputError.h"
#include "core/common/NumberText.h"
#include "core/geometry/MeshSlice.h"
#include "core/geometry/Polygon.h"
#include "core/io/MeshFile.h"
#include "core/scene/Scene.h"

namespace activetouch {

namespace {

/// `loop` without the vertices that lie on the line through their neighbours (within a
/// nanometre): a slice through a flat side gives a point where each triangle meets the next.
std::vector<Vec2> withoutCollinear(const std::vector<Vec2>& loop) {
    std::vector<Vec2> kept;
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = loop[(i + n - 1) % n], p = loop[i], b = loop[(i + 1) % n];
        const Vec2 ab = b - a, ap = p - a;
        const double length = std::hypot(ab.x, ab.y);
        if (length > 0 && std::abs(ab.x * ap.y - ab.y * ap.x) / length < 1e-6) continue;
        kept.push_back(p);
    }
    return kept.size() >= 3 ? kept : loop;
}

double unitsToMm(const JsonFields& f) {
    if (!f.has("units"))
        f.fail("units",
               "a mesh needs 'units': \"mm\", \"cm\", \"m\" or \"in\" (STL and OBJ files do not "
               "say theirs; printing software mostly writes mm, CAD exports often m)");
    const std::string u = f.text("units");
    if (u == "mm") return 1.0;
    if (u == "cm") return 10.0;
    if (u == "m") return 1000.0;
    if (u == "in") return 25.4;
    f.fail("units", "units '" + u + "' are none of mm, cm, m, in");
}

}  // namespace

MeshOutline meshOutline(const JsonFields& f, const std::string& baseDirectory) {
    if (f.has("top_height_mm"))
        f.fail("top_height_mm", "a mesh's top height comes from the mesh; leave it out");
    const std::string file = objectFilePath(f, baseDirectory);
    TriangleMesh mesh = readMeshFile(file, unitsToMm(f), f.source(), f.placeOf("file"));
    if (const auto problem = meshProblem(mesh))
        throw InputError(f.source(), f.placeOf("file"), "'" + file + "': " + *problem);
    const double bottom = mesh.lowestZ(), height = mesh.highestZ() - bottom;
    if (!(height > 0.1))
        f.fail("file", "the mesh is flat (" + numberText(height) + " mm high): no edge to follow");
    MeshOutline out;
    out.height_mm = height;
    const double slice = f.number("slice_height_mm", -1e6, 1e6,
                                  std::max(0.5 * height, height - kDefaultSliceDepth_mm));
    if (!(slice > 0.0 && slice < height))
        f.fail("slice_height_mm", "the slice at " + numberText(slice) +
                                      " mm lies outside the object, which stands " +
                                      numberText(height) + " mm high above its lowest point");
    std::vector<std::vector<Vec2>> loops = sliceMesh(mesh, bottom + slice);
    if (loops.empty())
        f.fail("slice_height_mm",
               "the slice at " + numberText(slice) + " mm meets no surface of the mesh");
    // The outer loop: the largest; the others are holes or separate parts.
    const auto outer =
        std::max_element(loops.begin(), loops.end(), [](const auto& a, const auto& b) {
            return std::abs(Polygon::signedArea(a)) < std::abs(Polygon::signedArea(b));
        });
    out.outline = centredOnBox(withoutCollinear(*outer));
    if (const auto problem = Polygon::problemWith(out.outline))
        f.fail("slice_height_mm",
               "the slice at " + numberText(slice) + " mm gives no usable outline: " + *problem);
    return out;
}

}  // namespace activetouch
