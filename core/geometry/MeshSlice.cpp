#include "core/geometry/MeshSlice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>
#include <utility>

#include "core/common/NumberText.h"

namespace activetouch {

namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;  ///< vertex indices, the lower first

Edge edgeOf(std::uint32_t a, std::uint32_t b) {
    return a < b ? Edge{a, b} : Edge{b, a};
}

std::string pointText(const std::array<double, 3>& p) {
    std::string text = "(";
    text += numberText(p[0]) + ", " + numberText(p[1]) + ", " + numberText(p[2]) + ") mm";
    return text;
}

bool degenerate(const std::array<std::uint32_t, 3>& t) {
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
}

}  // namespace

double TriangleMesh::lowestZ() const {
    double z = std::numeric_limits<double>::infinity();
    for (const auto& v : vertices) z = std::min(z, v[2]);
    return z;
}

double TriangleMesh::highestZ() const {
    double z = -std::numeric_limits<double>::infinity();
    for (const auto& v : vertices) z = std::max(z, v[2]);
    return z;
}

std::optional<std::string> meshProblem(const TriangleMesh& mesh) {
    if (mesh.triangles.empty()) return std::string("the mesh has no triangles");
    std::map<Edge, int> uses;
    for (const auto& t : mesh.triangles) {
        if (degenerate(t)) continue;
        for (int i = 0; i < 3; ++i) ++uses[edgeOf(t[i], t[(i + 1) % 3])];
    }
    for (const auto& [edge, count] : uses) {
        if (count == 2) continue;
        const std::string where = "the edge from " + pointText(mesh.vertices[edge.first]) + " to " +
                                  pointText(mesh.vertices[edge.second]);
        if (count == 1)
            return "the mesh is open: " + where +
                   " belongs to one triangle only; close the surface (a solid's mesh has every "
                   "edge shared by two triangles)";
        return "the mesh is not a manifold: " + where + " is shared by " + std::to_string(count) +
               " triangles; export the object as one closed solid";
    }
    return std::nullopt;
}

std::vector<std::vector<Vec2>> sliceMesh(const TriangleMesh& mesh, double z) {
    // Vertices on the plane count as above it: each triangle's crossing edges then have one end
    // strictly below and one above, so neighbouring triangles meet at the same edge points.
    auto above = [&](std::uint32_t v) { return mesh.vertices[v][2] >= z; };
    auto pointOn = [&](const Edge& e) {
        const auto& a = mesh.vertices[e.first];
        const auto& b = mesh.vertices[e.second];
        const double t = (z - a[2]) / (b[2] - a[2]);
        return Vec2{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
    };
    // Each crossing triangle gives a segment from one crossed edge to the other, ordered so that
    // the solid lies to the left (for an outward-facing mesh): the loops come out counter-
    // clockwise round material.
    std::map<Edge, Edge> next;
    for (const auto& t : mesh.triangles) {
        if (degenerate(t)) continue;
        std::vector<Edge> crossed;
        int from = -1;
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = t[i], b = t[(i + 1) % 3];
            if (above(a) == above(b)) continue;
            crossed.push_back(edgeOf(a, b));
            if (!above(a) && above(b)) from = static_cast<int>(crossed.size()) - 1;
        }
        if (crossed.size() != 2) continue;
        const Edge start = crossed[static_cast<std::size_t>(from)];
        const Edge end = crossed[static_cast<std::size_t>(1 - from)];
        next[start] = end;
    }
    std::vector<std::vector<Vec2>> loops;
    while (!next.empty()) {
        const Edge first = next.begin()->first;
        std::vector<Vec2> loop;
        Edge at = first;
        while (true) {
            const auto it = next.find(at);
            if (it == next.end()) break;  // an open mesh: meshProblem() names it
            loop.push_back(pointOn(at));
            at = it->second;
            next.erase(it);
            if (at == first) break;
        }
        if (loop.size() >= 3) loops.push_back(std::move(loop));
    }
    return loops;
}

}  // namespace activetouch
