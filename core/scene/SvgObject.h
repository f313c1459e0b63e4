#pragma once
// An object drawn in an SVG document (`"shape": "svg_file"`): the outline of one of its drawn
// elements, chosen by id or the largest closed outline (docs/file-formats.md).
#include <string>
#include <vector>

#include "core/geometry/Vec2.h"
#include "core/io/JsonFields.h"

namespace activetouch {

struct SvgFileOutline {
    std::vector<Vec2> outline;  ///< centred on its bounding box, y up, mm
    std::string element;        ///< which element it is ("path 'gear' (line 12)")
    /// The other closed outlines in the element (holes) and in the document, named, not followed.
    std::vector<std::string> others;
};

/// Reads the object fields "file", "element" (an id; optional) and "svg_tolerance_mm". Throws
/// InputError naming the field and the element (its id and line) where the document cannot be
/// read, the element named is not there or draws no closed outline, or no element does.
SvgFileOutline svgFileOutline(const JsonFields& f, const std::string& baseDirectory);

}  // namespace activetouch
