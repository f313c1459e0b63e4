#include "core/geometry/ShapeLibrary.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <stdexcept>

namespace activetouch {

const std::vector<std::string>& libraryShapeNames() {
    static const std::vector<std::string> names{"rectangle", "cross",    "C",        "L",
                                                "circle",    "ellipse",  "triangle", "star",
                                                "heart",     "teardrop", "clover",   "gear"};
    return names;
}

std::string libraryShapeList() {
    std::string list;
    for (const auto& n : libraryShapeNames()) list += (list.empty() ? "" : ", ") + n;
    return list;
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

bool shapeHasArms(const std::string& name) {
    return name == "cross" || name == "C" || name == "L";
}

std::optional<std::vector<Vec2>> unitShape(const std::string& name);

ShapeSize defaultShapeSize(const std::string& name) {
    if (name == "rectangle") return {48.0, 58.0, 0.0, 0.0};
    if (name == "ellipse") return {72.0, 44.0, 0.0, 0.0};
    if (name == "teardrop") return {50.0, 76.0, 0.0, 0.0};
    if (shapeHasArms(name)) return {60.0, 60.0, 20.0, 20.0};
    // The others keep their own proportions (a gear or a star stretched to a square box would
    // lose its symmetry): a width, and the height that goes with it.
    double width = 60.0;
    if (name == "triangle") width = 70.0;
    if (name == "star" || name == "gear") width = 84.0;
    if (name == "heart") width = 72.0;
    if (name == "clover") width = 80.0;
    if (const auto unit = unitShape(name)) {
        Vec2 lo = unit->front(), hi = lo;
        for (Vec2 p : *unit) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
        }
        return {width, width * (hi.y - lo.y) / (hi.x - lo.x), 0.0, 0.0};
    }
    return {60.0, 60.0, 0.0, 0.0};
}

namespace {

constexpr double kPi = 3.14159265358979323846;

/// `points` scaled and moved so that their bounding box is w x h centred on the origin.
Polygon fittedToBox(std::vector<Vec2> points, double w, double h) {
    Vec2 lo = points.front(), hi = lo;
    for (Vec2 p : points) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const Vec2 c = 0.5 * (lo + hi);
    for (Vec2& p : points) p = {(p.x - c.x) * w / (hi.x - lo.x), (p.y - c.y) * h / (hi.y - lo.y)};
    return Polygon(std::move(points));
}

/// A closed curve sampled at `n` parameter values over one turn.
std::vector<Vec2> sampled(int n, const std::function<Vec2(double)>& curve) {
    std::vector<Vec2> points;
    for (int i = 0; i < n; ++i) points.push_back(curve(2.0 * kPi * i / n));
    return points;
}

/// A curve given by its radius at each polar angle.
std::vector<Vec2> polar(int n, const std::function<double(double)>& radius) {
    return sampled(n, [&](double t) { return radius(t) * Vec2{std::cos(t), std::sin(t)}; });
}

/// The gear's radius at polar angle `t`: six teeth, each a flat top between straight flanks.
double gearRadius(double t) {
    const double pitch = 2.0 * kPi / 6, top = 16.0 / 60, flank = 8.0 / 60;  // shares of a pitch
    const double root = 0.72;
    double u = std::fmod(t, pitch) / pitch;  // 0..1 within the pitch, tooth top centred on 0
    if (u > 0.5) u = 1.0 - u;
    if (u <= top / 2) return 1.0;
    if (u >= top / 2 + flank) return root;
    return 1.0 - (1.0 - root) * (u - top / 2) / flank;
}

}  // namespace

/// The curves and polygons beyond the paper's four, before scaling to their box.
std::optional<std::vector<Vec2>> unitShape(const std::string& name) {
    if (name == "circle" || name == "ellipse")
        return sampled(144, [](double t) { return Vec2{std::cos(t), std::sin(t)}; });
    if (name == "triangle")
        return std::vector<Vec2>{{0.0, 1.0}, {-std::sqrt(0.75), -0.5}, {std::sqrt(0.75), -0.5}};
    if (name == "star") {
        std::vector<Vec2> v;
        for (int i = 0; i < 10; ++i) {
            const double r = i % 2 == 0 ? 1.0 : 0.62, a = kPi / 2 + i * kPi / 5;
            v.push_back(r * Vec2{std::cos(a), std::sin(a)});
        }
        return v;
    }
    if (name == "heart") {
        // Two round lobes (unit circles 1.2 apart) meeting in a notch at the top, their outer
        // sides joined by tangent lines to the point at the bottom: every part of it is one a
        // fingertip can follow (the notch turns by 74 degrees, less than the cross's corners).
        const Vec2 tip{0.0, -2.2}, right{0.6, 0.0}, left{-0.6, 0.0};
        const double toTip = std::atan2(tip.y - right.y, tip.x - right.x);
        const double touch = toTip + std::acos(1.0 / distance(tip, right));  // right tangent point
        const double notch = std::atan2(0.8, -0.6);                          // from right's centre
        std::vector<Vec2> v{tip};
        const int steps = 72;
        for (int i = 0; i <= steps; ++i) {  // the right lobe, counter-clockwise to the notch
            const double a = touch + (notch - touch) * i / steps;
            v.push_back(right + Vec2{std::cos(a), std::sin(a)});
        }
        for (int i = 1; i <= steps; ++i) {  // the left lobe, from the notch round to its tangent
            const double a = (kPi - notch) + (notch - touch) * i / steps;
            v.push_back(left + Vec2{std::cos(a), std::sin(a)});
        }
        return v;
    }
    if (name == "teardrop")  // the point up
        return sampled(144, [](double t) {
            return Vec2{-std::sin(t) * std::sin(t / 2), std::cos(t)};
        });
    if (name == "clover")  // four round leaves on the diagonals
        return polar(192, [](double t) { return 0.75 + 0.25 * std::cos(4 * (t - kPi / 4)); });
    if (name == "gear") return polar(180, gearRadius);
    return std::nullopt;
}

Polygon libraryShape(const std::string& name, const ShapeSize& s) {
    const double w = s.width, h = s.height, a = s.arm;
    if (!(w > 0) || !(h > 0)) throw std::invalid_argument("width and height must be positive");
    const double x0 = -w / 2, y0 = -h / 2;
    auto at = [&](double x, double y) { return Vec2{x0 + x, y0 + y}; };
    if (name == "rectangle") return Polygon({at(0, 0), at(w, 0), at(w, h), at(0, h)});
    if (const auto unit = unitShape(name)) return fittedToBox(*unit, w, h);
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
                                "'; use one of the library's shapes or give a polygon");
}

}  // namespace activetouch
