#pragma once
// Whole SVG documents as drawing programs write them (Inkscape, CAD exports), read with SVG++
// (Debian's libsvgpp-dev) over libxml2: the viewBox and the document's physical size, nested
// transforms and the basic shapes (rect with rounded corners, circle, ellipse, polygon,
// polyline, line) as well as paths. Each element's path comes out in its own user space with the
// transform that maps it into mm, so that arcs are flattened by the project's own path reader
// (core/geometry/SvgPath.h, which takes degenerate radii as SVG specifies) before the transform.
#include <array>
#include <string>
#include <vector>

namespace activetouch {

/// One drawn element: its kind ("path", "rect", ...), id (empty if none) and line in the file,
/// its subpaths as SVG path data in its own user space (absolute M, L, Q, C, A and Z), and the
/// affine map from there into the document's mm (y down, as drawn): x' = a x + c y + e,
/// y' = b x + d y + f.
struct SvgElement {
    std::string kind, id;
    int line = 0;
    std::vector<std::string> subpaths;
    std::array<double, 6> toMm{1, 0, 0, 1, 0, 0};  ///< a b c d e f
    /// "rect 'r' (line 4)" or "path (line 9)", for messages.
    std::string name() const;
};

/// A document larger than this is refused before it is read.
inline constexpr unsigned long long kMaxSvgFileBytes = 16ull << 20;

/// Every drawn element of the document at `path`, in document order (elements inside defs,
/// symbol, clipPath and the like are not drawn and not read). Throws InputError naming `source`
/// and `place` (the setting that named the file) with the file and line where it is not an SVG
/// document SVG++ can read.
std::vector<SvgElement> readSvgDocument(const std::string& path, const std::string& source,
                                        const std::string& place);

}  // namespace activetouch
