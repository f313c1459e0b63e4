#include "core/geometry/ShapeLibrary.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace activetouch {

const std::vector<std::string>& libraryShapeNames() {
    static const std::vector<std::string> names{"rectangle", "cross", "C", "L"};
    return names;
}

std::optional<std::string> libraryShapeName(const std::string& name) {
    auto lower = [](std::string s) {
        std::transform(s.begin(), s.end(), s.begin(),
                       [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
        return s;
    };
    for (const auto& n : libraryShapeNames())
        if (lower(n) == lower(name)) return n;
    return std::nullopt;
}

ShapeSize defaultShapeSize(const std::string& name) {
    if (name == "rectangle") return {48.0, 58.0, 0.0, 0.0};
    return {60.0, 60.0, 20.0, 20.0};
}

Polygon libraryShape(const std::string& name, const ShapeSize& s) {
    const double w = s.width, h = s.height, a = s.arm;
    if (!(w > 0) || !(h > 0)) throw std::invalid_argument("width and height must be positive");
    const double x0 = -w / 2, y0 = -h / 2;
    auto at = [&](double x, double y) { return Vec2{x0 + x, y0 + y}; };
    if (name == "rectangle") return Polygon({at(0, 0), at(w, 0), at(w, h), at(0, h)});
    if (!(a > 0)) throw std::invalid_argument("arm width must be positive");
    if (name == "cross") {
        if (a >= w || a >= h)
            throw std::invalid_argument("the cross's arm must be narrower than the shape");
        const double xa = (w - a) / 2, ya = (h - a) / 2;
        return Polygon({at(xa, 0), at(xa + a, 0), at(xa + a, ya), at(w, ya), at(w, ya + a),
                        at(xa + a, ya + a), at(xa + a, h), at(xa, h), at(xa, ya + a), at(0, ya + a),
                        at(0, ya), at(xa, ya)});
    }
    if (name == "C") {
        const double gap = s.opening;
        if (!(gap > 0) || a >= w || gap >= h)
            throw std::invalid_argument("the C needs 0 < opening < height and arm < width");
        const double yb = (h - gap) / 2;
        return Polygon({at(0, 0), at(w, 0), at(w, yb), at(a, yb), at(a, yb + gap), at(w, yb + gap),
                        at(w, h), at(0, h)});
    }
    if (name == "L") {
        if (a >= w || a >= h)
            throw std::invalid_argument("the L's arm must be narrower than the shape");
        return Polygon({at(0, 0), at(w, 0), at(w, a), at(a, a), at(a, h), at(0, h)});
    }
    throw std::invalid_argument("unknown shape '" + name +
                                "'; use rectangle, cross, C, L or give a polygon");
}

}  // namespace activetouch
