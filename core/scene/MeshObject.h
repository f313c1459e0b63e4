#pragma once
// An object given as a triangle mesh (a 3D-printed part's STL or OBJ): the outline where a
// horizontal plane near its top cuts it, and its height (docs/file-formats.md, "mesh").
#include <string>
#include <vector>

#include "core/geometry/Vec2.h"
#include "core/io/JsonFields.h"

namespace activetouch {

/// A mesh is sliced this far under its top unless the scene says where: the fingertip's pad
/// meets the object's edge just under the top face.
inline constexpr double kDefaultSliceDepth_mm = 0.5;

struct MeshOutline {
    std::vector<Vec2> outline;  ///< the outer loop, centred on its bounding box
    double height_mm = 0.0;     ///< the mesh's top above its lowest point (on the table)
};

/// Reads the object fields "file", "units" ("mm", "cm", "m" or "in") and "slice_height_mm"
/// (above the mesh's lowest point) and slices the mesh there. Throws InputError naming the
/// field: a file that is no closed mesh (naming the open or shared edge), a slice above the top
/// or below the bottom, or one that meets no surface or no usable outline.
MeshOutline meshOutline(const JsonFields& f, const std::string& baseDirectory);

}  // namespace activetouch
