#pragma once
// An object outline from SVG path data (the `d` of a <path>): moves, lines (L, H, V), quadratic
// and cubic Béziers (Q, T, C, S) and elliptical arcs (A), relative and absolute, flattened to a
// polygon whose every point lies within a stated tolerance of the curve. Units are millimetres
// (SVG user units taken as mm). One closed outline only: what cannot be one is refused with the
// place in the path data.
#include <string>

#include "core/geometry/Polygon.h"

namespace activetouch {

/// The largest |coordinate| path data may use, mm: an object on the stage is far smaller.
inline constexpr double kMaxSvgCoordinate_mm = 10000.0;
/// The flattening tolerance a scene gets unless it says otherwise, mm.
inline constexpr double kDefaultSvgTolerance_mm = 0.05;

/// The outline `d` describes, each curve flattened to within `tolerance_mm` (> 0). Throws
/// InputError(source, place, problem) naming the place ("<place>, character N (command X)") for
/// an unknown command, a malformed number or flag, a missing argument, a coordinate that is not
/// finite or beyond kMaxSvgCoordinate_mm, more than kMaxOutlineVertices points, a second subpath, a
/// path that does not close (no Z and not ending where it began), or an outline of no length, no
/// area or that crosses itself.
Polygon polygonFromSvgPath(const std::string& d, double tolerance_mm, const std::string& source,
                           const std::string& place);

}  // namespace activetouch
