#pragma once
// A point or displacement in the stage plane, millimetres. World frame: x right, y up.
#include <cmath>

namespace activetouch {

struct Vec2 {
    double x = 0.0;
    double y = 0.0;

    friend Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
    friend Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
    friend Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
    friend Vec2 operator*(Vec2 a, double s) { return {s * a.x, s * a.y}; }
    friend bool operator==(Vec2 a, Vec2 b) = default;
    Vec2& operator+=(Vec2 b) {
        x += b.x;
        y += b.y;
        return *this;
    }
};

inline double dot(Vec2 a, Vec2 b) {
    return a.x * b.x + a.y * b.y;
}
inline double cross(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}
// Millimetre-scale values never approach overflow, so plain sqrt (not hypot) is safe and fast.
inline double norm(Vec2 a) {
    return std::sqrt(a.x * a.x + a.y * a.y);
}
inline double distance(Vec2 a, Vec2 b) {
    return norm(a - b);
}

/// Unit vector at `degrees` counter-clockwise from +x; exact for multiples of 90 degrees, so that
/// moves along axis-aligned edges stay on the millimetre grid.
inline Vec2 directionFromDegrees(double degrees) {
    double d = std::fmod(degrees, 360.0);
    if (d < 0) d += 360.0;
    if (d == 0.0) return {1.0, 0.0};
    if (d == 90.0) return {0.0, 1.0};
    if (d == 180.0) return {-1.0, 0.0};
    if (d == 270.0) return {0.0, -1.0};
    const double r = degrees * M_PI / 180.0;
    return {std::cos(r), std::sin(r)};
}

/// The direction of `v` as an angle counter-clockwise from +x, degrees in [0, 360).
inline double degreesOf(Vec2 v) {
    const double d = std::atan2(v.y, v.x) * 180.0 / M_PI;
    return d < 0.0 ? (d + 360.0 >= 360.0 ? 0.0 : d + 360.0) : d;
}

inline Vec2 rotated(Vec2 v, double degrees) {
    const double r = degrees * M_PI / 180.0;
    const double c = std::cos(r), s = std::sin(r);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

}  // namespace activetouch
