#include "core/scene/SvgObject.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/common/InputError.h"
#include "core/geometry/Polygon.h"
#include "core/geometry/SvgPath.h"
#include "core/io/SvgDocument.h"
#include "core/scene/Scene.h"

namespace activetouch {

namespace {

struct Closed {
    Polygon polygon;
    std::string name;
};

/// How far the element's map into mm stretches any length at most (its largest singular value).
double largestStretch(const std::array<double, 6>& m) {
    const double t = m[0] * m[0] + m[1] * m[1] + m[2] * m[2] + m[3] * m[3];
    const double det = m[0] * m[3] - m[1] * m[2];
    return std::sqrt(0.5 * (t + std::sqrt(std::max(0.0, t * t - 4.0 * det * det))));
}

/// A subpath of `e` flattened in the element's own user space (within `tolerance` mm once mapped)
/// and mapped into mm; throws InputError naming `name` if it is no usable outline.
Polygon outlineOf(const SvgElement& e, const std::string& subpath, double tolerance,
                  const std::string& file, const std::string& name) {
    const double stretch = largestStretch(e.toMm);
    if (!(stretch > 0.0) || !std::isfinite(stretch))
        throw InputError(file, name, "its transforms collapse it to nothing");
    const Polygon local = polygonFromSvgPath(subpath, tolerance / stretch, file, name);
    const auto& m = e.toMm;
    std::vector<Vec2> mapped;
    for (const Vec2& v : local.vertices())
        mapped.push_back({m[0] * v.x + m[2] * v.y + m[4], m[1] * v.x + m[3] * v.y + m[5]});
    if (const auto problem = Polygon::problemWith(mapped))
        throw InputError(file, name, "the outline it draws cannot be an object: " + *problem);
    return Polygon(std::move(mapped));
}

/// The closed outlines `e` draws, flattened within `tolerance`; with `refusal`, the first
/// reason one of its subpaths is not a usable outline.
std::vector<Closed> closedOutlines(const SvgElement& e, double tolerance, const std::string& file,
                                   std::string* refusal) {
    std::vector<Closed> out;
    for (std::size_t i = 0; i < e.subpaths.size(); ++i) {
        const std::string name =
            e.name() + (e.subpaths.size() > 1 ? ", subpath " + std::to_string(i + 1) : "");
        try {
            out.push_back({outlineOf(e, e.subpaths[i], tolerance, file, name), name});
        } catch (const InputError& err) {
            if (refusal && refusal->empty()) *refusal = name + ": " + err.problem();
        }
    }
    return out;
}

}  // namespace

SvgFileOutline svgFileOutline(const JsonFields& f, const std::string& baseDirectory) {
    const std::string file = objectFilePath(f, baseDirectory);
    const double tolerance = f.number("svg_tolerance_mm", 0.001, 5.0, kDefaultSvgTolerance_mm);
    const std::vector<SvgElement> elements = readSvgDocument(file, f.source(), f.placeOf("file"));
    const std::string wanted = f.has("element") ? f.text("element") : std::string();
    std::vector<Closed> all;
    std::string refusal, ids;
    bool found = false;
    for (const SvgElement& e : elements) {
        if (!e.id.empty()) ids += (ids.empty() ? "" : ", ") + e.id;
        const bool chosen = !wanted.empty() && e.id == wanted;
        found = found || chosen;
        if (!wanted.empty() && !chosen) continue;
        auto closed = closedOutlines(e, tolerance, file, &refusal);
        if (chosen && closed.empty())
            f.fail("element", "the element " + e.name() +
                                  " draws no closed outline the fingertip can follow" +
                                  (refusal.empty() ? std::string() : " (" + refusal + ")"));
        for (auto& c : closed) all.push_back(std::move(c));
    }
    if (!wanted.empty() && !found)
        f.fail("element", "'" + file + "' has no element with id '" + wanted + "'" +
                              (ids.empty() ? "; it names none" : "; its ids: " + ids));
    if (all.empty())
        f.fail("file", "'" + file + "' draws no closed outline" +
                           (refusal.empty() ? std::string() : " (" + refusal + ")"));
    std::sort(all.begin(), all.end(), [](const Closed& a, const Closed& b) {
        return std::abs(a.polygon.area()) > std::abs(b.polygon.area());
    });
    SvgFileOutline out{centredOnBox(all.front().polygon.vertices(), true), all.front().name, {}};
    for (std::size_t i = 1; i < all.size(); ++i) out.others.push_back(all[i].name);
    return out;
}

}  // namespace activetouch
