#pragma once
// A simple polygon: the outline of a flat object's top face. Vertices are stored counter-
// clockwise, so the outward normal of edge i is the edge direction turned clockwise.
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/Vec2.h"

namespace activetouch {

/// The most vertices an outline may have (docs/limits.md): a 0.1 mm chord along a 300 mm object
/// is 3,000; a fingertip resolves nothing finer.
inline constexpr std::size_t kMaxOutlineVertices = 10000;

/// `vertices` moved so that their bounding box is centred on the origin, y turned over where
/// `flipY` (a drawing's y axis points down): an outline drawn elsewhere, as an object keeps it.
std::vector<Vec2> centredOnBox(const std::vector<Vec2>& vertices, bool flipY = false);

class Polygon {
public:
    Polygon() = default;

    /// Builds a polygon from vertices in either winding. Throws std::invalid_argument with a
    /// sentence if the outline is degenerate (fewer than 3 distinct vertices, zero area, repeated
    /// consecutive vertices), self-intersecting or over kMaxOutlineVertices; see `problemWith`.
    explicit Polygon(std::vector<Vec2> vertices);

    /// Why `vertices` cannot be an object outline, or nothing if they can.
    static std::optional<std::string> problemWith(const std::vector<Vec2>& vertices);

    /// The area `vertices` enclose, positive where they run counter-clockwise.
    static double signedArea(const std::vector<Vec2>& vertices);

    const std::vector<Vec2>& vertices() const { return vertices_; }
    std::size_t size() const { return vertices_.size(); }
    Vec2 vertex(std::size_t i) const { return vertices_[i % vertices_.size()]; }

    double area() const;
    double perimeter() const { return cumulativeLength_.empty() ? 0.0 : cumulativeLength_.back(); }
    Vec2 boundingBoxMin() const { return min_; }
    Vec2 boundingBoxMax() const { return max_; }

    /// Even-odd point-in-polygon test.
    bool contains(Vec2 p) const;

    /// Distance to the outline, positive inside the object and negative outside.
    double signedDistance(Vec2 p) const;

    /// The point on the outline nearest to `p`, with its arc-length position measured counter-
    /// clockwise from vertex 0, and the index of the edge it lies on.
    struct OutlinePoint {
        Vec2 point;
        double arcLength = 0.0;
        std::size_t edge = 0;
        double distance = 0.0;
    };
    OutlinePoint nearestOutlinePoint(Vec2 p) const;

    /// The outline point at arc length `s` (wrapped to the perimeter).
    Vec2 pointAtArcLength(double s) const;

    /// Arc length of vertex i, counter-clockwise from vertex 0.
    double arcLengthOfVertex(std::size_t i) const { return cumulativeLength_[i % size()]; }

    /// How far the outline turns at vertex i, degrees in (-180, 180): positive where it turns
    /// left (a convex corner, counter-clockwise), negative where it turns right (concave).
    double turnDeg(std::size_t i) const;

    /// Outward unit normal of edge i (from vertex i to vertex i + 1).
    Vec2 outwardNormal(std::size_t edge) const;

    /// Rotates by `degrees` about the origin, then translates by `offset`.
    Polygon transformed(double degrees, Vec2 offset) const;

    /// The outline offset outward by `distance` (mitred corners for convex vertices, the
    /// inner offset lines intersected for concave ones). Used for ideal following paths.
    std::vector<Vec2> offsetOutline(double distance) const;

private:
    struct MovedWhole {};  ///< the vertices of a checked outline, rotated and moved
    Polygon(std::vector<Vec2> vertices, MovedWhole);
    void adopt(std::vector<Vec2> vertices);

    std::vector<Vec2> vertices_;
    std::vector<double> cumulativeLength_;  // arc length at the start of each edge, plus total
    Vec2 min_, max_;
};

}  // namespace activetouch
