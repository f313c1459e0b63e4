#pragma once
// An object's outline from a file, told apart by its name's ending (the window's Load outline):
// a JSON polygon, object or scene (.json), an SVG drawing (.svg: the largest closed outline it
// draws) or a mesh (.stl, .obj: sliced under its top, in the units given).
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/Vec2.h"

namespace activetouch {

struct OutlineFile {
    std::vector<Vec2> polygon;        ///< object frame, mm, centred as the scene reads it
    std::optional<double> height_mm;  ///< a mesh's own height; nothing for flat drawings
    std::string description;          ///< "path 'rim' (line 4) of plate.svg"
    std::vector<std::string> notes;   ///< what the file holds beside it (holes, other outlines)
};

/// Whether `path` names a mesh (.stl or .obj, any case): its units must be given.
bool isMeshFileName(const std::string& path);

/// Reads `path` by its ending; a mesh in `meshUnits` ("mm", "cm", "m" or "in"). Throws InputError
/// naming the file and, for a drawing, the element and why; nothing is changed on failure.
OutlineFile loadOutlineFile(const std::string& path, const std::string& meshUnits = "");

}  // namespace activetouch
