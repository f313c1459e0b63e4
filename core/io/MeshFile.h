#pragma once
// Triangle meshes as labs keep their 3D-printed objects: STL (binary or ASCII) and OBJ, read
// here (docs/design.md says why not with a mesh library), vertices at one place welded into one
// so that the surface's edges are shared (an STL repeats each vertex for every triangle).
#include <string>

#include "core/geometry/MeshSlice.h"

namespace activetouch {

/// A mesh file larger than this is refused before it is read: a printed object's STL at a fine
/// resolution is a few MB.
inline constexpr unsigned long long kMaxMeshFileBytes = 256ull << 20;

/// Reads `path`, its coordinates in `unitsToMm` mm each (1000 for metres, 1 for mm). Throws
/// InputError naming the file (and `place`, the setting that named it), and the line or
/// triangle, if it is no .stl or .obj file, cannot be read, is malformed, holds no triangle, has
/// a coordinate beyond 100 m, or is over kMaxMeshFileBytes.
TriangleMesh readMeshFile(const std::string& path, double unitsToMm, const std::string& source,
                          const std::string& place);

}  // namespace activetouch
