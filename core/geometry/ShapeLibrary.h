#pragma once
// The library's outlines, centred on their bounding box. The paper's four test objects first: the
// paper gives only the rectangle's size (48 x 58 mm); the cross, C and L default to 60 x 60 mm
// with 20 mm arms and a 20 mm C opening (docs/design.md §3). Then general shapes, each drawn to
// fill a width x height box: circle, ellipse, triangle, a five-pointed star, heart, teardrop
// (point up), a four-leaved clover and a six-toothed gear (docs/general-shapes.md). Curves are
// polygons of 144 to 192 vertices. Any scene may give its own polygon or SVG path instead.
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/Polygon.h"

namespace activetouch {

struct ShapeSize {
    double width = 60.0;    ///< bounding box along x, mm
    double height = 60.0;   ///< bounding box along y, mm
    double arm = 20.0;      ///< arm width for cross, C and L, mm
    double opening = 20.0;  ///< gap of the C, mm
};

/// The library's shapes as they are named everywhere: rectangle, cross, C, L, circle, ...
const std::vector<std::string>& libraryShapeNames();

/// The library's names as a list for messages: "rectangle, cross, C, L, circle, ...".
std::string libraryShapeList();

/// The library's name for `name` in any letter case ("c" -> "C"), or none if it names no
/// library shape.
std::optional<std::string> libraryShapeName(const std::string& name);

/// Outline of a library shape (named as libraryShapeNames() names it) centred at the origin. Throws
/// std::invalid_argument with a sentence for an unknown name or sizes that make no outline (arm
/// wider than the shape...).
Polygon libraryShape(const std::string& name, const ShapeSize& size);

/// Whether the shape has an arm width (cross, C, L).
bool shapeHasArms(const std::string& name);

/// The defaults docs/design.md gives for each library shape.
ShapeSize defaultShapeSize(const std::string& name);

}  // namespace activetouch
