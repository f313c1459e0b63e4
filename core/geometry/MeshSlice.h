#pragma once
// A closed triangle mesh (a 3D-printed object, read by core/io/MeshFile.h) cut by a horizontal
// plane into the loops where the plane meets its surface: the outline a fingertip pressing at
// that height follows.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/Vec2.h"

namespace activetouch {

/// Vertices in mm (z up) and triangles as indices into them; vertices at one place are one.
struct TriangleMesh {
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    double lowestZ() const;
    double highestZ() const;
};

/// Why `mesh` is not the closed surface of a solid, naming the first place it fails: an edge
/// that only one triangle has (the mesh is open there), or that more than two share (it is not
/// a manifold); a triangle with no area is skipped, not refused. Nothing if it is closed.
std::optional<std::string> meshProblem(const TriangleMesh& mesh);

/// The loops where the plane at height `z` cuts the closed `mesh`, each a list of vertices (x,
/// y, mm) in order round it. A vertex lying exactly on the plane is taken as just above it, so
/// that every loop is cut through edges. Empty where the plane misses the mesh.
std::vector<std::vector<Vec2>> sliceMesh(const TriangleMesh& mesh, double z);

}  // namespace activetouch
