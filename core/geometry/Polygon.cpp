#include "core/geometry/Polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace activetouch {
double Polygon::signedArea(const std::vector<Vec2>& v) {
    double a = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) a += cross(v[i], v[(i + 1) % v.size()]);
    return 0.5 * a;
}

std::vector<Vec2> centredOnBox(const std::vector<Vec2>& vertices, bool flipY) {
    if (vertices.empty()) return {};
    Vec2 lo = vertices.front(), hi = lo;
    for (const Vec2& v : vertices) {
        lo = {std::min(lo.x, v.x), std::min(lo.y, v.y)};
        hi = {std::max(hi.x, v.x), std::max(hi.y, v.y)};
    }
    const Vec2 centre = 0.5 * (lo + hi);
    std::vector<Vec2> out;
    out.reserve(vertices.size());
    for (const Vec2& v : vertices)
        out.push_back({v.x - centre.x, flipY ? centre.y - v.y : v.y - centre.y});
    return out;
}

namespace {

int orientation(Vec2 a, Vec2 b, Vec2 c) {
    const double v = cross(b - a, c - a);
    const double scale = std::max({norm(b - a), norm(c - a), 1.0});
    if (std::abs(v) <= 1e-12 * scale * scale) return 0;
    return v > 0 ? 1 : -1;
}

bool onSegment(Vec2 a, Vec2 b, Vec2 p) {
    return std::min(a.x, b.x) - 1e-12 <= p.x && p.x <= std::max(a.x, b.x) + 1e-12 &&
           std::min(a.y, b.y) - 1e-12 <= p.y && p.y <= std::max(a.y, b.y) + 1e-12;
}

bool segmentsIntersect(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2) {
    const int o1 = orientation(p1, p2, q1), o2 = orientation(p1, p2, q2);
    const int o3 = orientation(q1, q2, p1), o4 = orientation(q1, q2, p2);
    if (o1 != o2 && o3 != o4) return true;
    if (o1 == 0 && onSegment(p1, p2, q1)) return true;
    if (o2 == 0 && onSegment(p1, p2, q2)) return true;
    if (o3 == 0 && onSegment(q1, q2, p1)) return true;
    if (o4 == 0 && onSegment(q1, q2, p2)) return true;
    return false;
}

// Beyond this, squared lengths lose the precision the outline tests need (and no stage is that
// big).
constexpr double kMaxCoordinate_mm = 1e6;

std::string vertexText(std::size_t i, Vec2 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "vertex %zu (%.6g, %.6g)", i, v.x, v.y);
    return buf;
}

}  // namespace

namespace {

// Why the cheap per-vertex tests refuse `v` (O(n)), or nothing.
std::optional<std::string> vertexProblem(const std::vector<Vec2>& v) {
    if (v.size() < 3)
        return "an outline needs at least 3 vertices, got " + std::to_string(v.size());
    if (v.size() > kMaxOutlineVertices)
        return "an outline may have at most " + std::to_string(kMaxOutlineVertices) +
               " vertices, got " + std::to_string(v.size()) +
               "; no fingertip resolves detail that fine, so thin the outline";
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y))
            return vertexText(i, v[i]) + " is not a finite number";
        if (std::abs(v[i].x) > kMaxCoordinate_mm || std::abs(v[i].y) > kMaxCoordinate_mm)
            return vertexText(i, v[i]) +
                   " lies more than 1 km from the origin; vertices are in millimetres";
        if (distance(v[i], v[(i + 1) % v.size()]) < 1e-9)
            return vertexText(i, v[i]) + " repeats the next vertex; remove the duplicate";
    }
    return std::nullopt;
}

// The problem of edges i < j (edge k runs from vertex k to k + 1), or nothing.
std::optional<std::string> edgePairProblem(const std::vector<Vec2>& v, std::size_t i,
                                           std::size_t j) {
    const std::size_t n = v.size();
    const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
    if (adjacent) {
        // Adjacent edges share a vertex; they may only touch there (no folding back).
        const Vec2 shared = (j == i + 1) ? v[j] : v[i];
        const Vec2 a0 = (j == i + 1) ? v[i] : v[(i + 1) % n];
        const Vec2 b1 = (j == i + 1) ? v[(j + 1) % n] : v[j];
        if (orientation(a0, shared, b1) == 0 && dot(a0 - shared, b1 - shared) > 0)
            return "edges at " + vertexText(i == 0 && j == n - 1 ? 0 : j, shared) +
                   " fold back onto each other";
        return std::nullopt;
    }
    if (segmentsIntersect(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n]))
        return "the outline intersects itself: the edge from " + vertexText(i, v[i]) +
               " crosses the edge from " + vertexText(j, v[j]);
    return std::nullopt;
}

// The first pair of edges (in the order i, then j) that cross or fold back, found by sweeping
// the edges' x-extents: only edges whose boxes overlap are tested, so an outline of thousands of
// vertices is checked in milliseconds.
std::optional<std::string> crossingProblem(const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    struct Box {
        double minX, maxX, minY, maxY;
        std::size_t edge;
    };
    std::vector<Box> boxes(n);
    constexpr double slack = 1e-9;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = v[i], b = v[(i + 1) % n];
        boxes[i] = {std::min(a.x, b.x) - slack, std::max(a.x, b.x) + slack,
                    std::min(a.y, b.y) - slack, std::max(a.y, b.y) + slack, i};
    }
    std::sort(boxes.begin(), boxes.end(),
              [](const Box& a, const Box& b) { return a.minX < b.minX; });
    std::optional<std::pair<std::size_t, std::size_t>> first;
    std::optional<std::string> problem;
    for (std::size_t k = 0; k < n; ++k) {
        for (std::size_t m = k + 1; m < n && boxes[m].minX <= boxes[k].maxX; ++m) {
            if (boxes[m].minY > boxes[k].maxY || boxes[k].minY > boxes[m].maxY) continue;
            const std::size_t i = std::min(boxes[k].edge, boxes[m].edge);
            const std::size_t j = std::max(boxes[k].edge, boxes[m].edge);
            if (first && std::pair(i, j) >= *first) continue;
            if (auto p = edgePairProblem(v, i, j)) {
                first = std::pair(i, j);
                problem = std::move(p);
            }
        }
    }
    return problem;
}

// The outlines checked last: an object's outline is asked for again and again (every trial,
// every check), and one of thousands of vertices is checked once.
class CheckedOutlines {
public:
    std::optional<std::optional<std::string>> find(const std::vector<Vec2>& v) {
        std::lock_guard lock(mutex_);
        for (const auto& [vertices, problem] : entries_)
            if (vertices == v) return problem;
        return std::nullopt;
    }
    void add(const std::vector<Vec2>& v, const std::optional<std::string>& problem) {
        std::lock_guard lock(mutex_);
        if (entries_.size() >= 8) entries_.erase(entries_.begin());
        entries_.emplace_back(v, problem);
    }

private:
    std::mutex mutex_;
    std::vector<std::pair<std::vector<Vec2>, std::optional<std::string>>> entries_;
};

CheckedOutlines& checkedOutlines() {
    static CheckedOutlines outlines;
    return outlines;
}

}  // namespace

std::optional<std::string> Polygon::problemWith(const std::vector<Vec2>& v) {
    if (auto problem = vertexProblem(v)) return problem;
    const bool remembered = v.size() >= 64;  // small outlines cost less to check than to look up
    if (remembered)
        if (auto known = checkedOutlines().find(v)) return *known;
    std::optional<std::string> problem;
    bool collinear = true;
    for (std::size_t i = 2; i < v.size() && collinear; ++i)
        collinear = orientation(v[0], v[1], v[i]) == 0;
    if (collinear)
        problem = "the outline encloses no area (all vertices on one line)";
    else if (auto crossing = crossingProblem(v))
        problem = std::move(crossing);
    else if (!(std::abs(signedArea(v)) > 1e-9))
        problem = "the outline encloses no area";
    if (remembered) checkedOutlines().add(v, problem);
    return problem;
}

Polygon::Polygon(std::vector<Vec2> vertices) {
    if (auto problem = problemWith(vertices)) throw std::invalid_argument(*problem);
    adopt(std::move(vertices));
}

Polygon::Polygon(std::vector<Vec2> vertices, MovedWhole) {
    // A rotation and a translation keep a simple outline simple: only what depends on where the
    // vertices now lie is checked again.
    if (auto problem = vertexProblem(vertices)) throw std::invalid_argument(*problem);
    adopt(std::move(vertices));
}

void Polygon::adopt(std::vector<Vec2> vertices) {
    if (signedArea(vertices) < 0) std::reverse(vertices.begin(), vertices.end());
    vertices_ = std::move(vertices);
    cumulativeLength_.resize(vertices_.size() + 1, 0.0);
    min_ = max_ = vertices_.front();
    for (std::size_t i = 0; i < vertices_.size(); ++i) {
        cumulativeLength_[i + 1] = cumulativeLength_[i] + distance(vertex(i), vertex(i + 1));
        min_ = {std::min(min_.x, vertices_[i].x), std::min(min_.y, vertices_[i].y)};
        max_ = {std::max(max_.x, vertices_[i].x), std::max(max_.y, vertices_[i].y)};
    }
}

double Polygon::area() const {
    return std::abs(signedArea(vertices_));
}

bool Polygon::contains(Vec2 p) const {
    bool inside = false;
    const std::size_t n = vertices_.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const Vec2 a = vertices_[i], b = vertices_[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
            inside = !inside;
    }
    return inside;
}

Polygon::OutlinePoint Polygon::nearestOutlinePoint(Vec2 p) const {
    OutlinePoint best;
    best.distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < vertices_.size(); ++i) {
        const Vec2 a = vertex(i), b = vertex(i + 1);
        const Vec2 ab = b - a;
        const double len2 = dot(ab, ab);
        const double t = std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
        const Vec2 q = a + t * ab;
        const double d = distance(p, q);
        if (d < best.distance) {
            best = {q, cumulativeLength_[i] + t * std::sqrt(len2), i, d};
        }
    }
    return best;
}

double Polygon::signedDistance(Vec2 p) const {
    const double d = nearestOutlinePoint(p).distance;
    return contains(p) ? d : -d;
}

Vec2 Polygon::pointAtArcLength(double s) const {
    const double total = perimeter();
    s = std::fmod(s, total);
    if (s < 0) s += total;
    auto it = std::upper_bound(cumulativeLength_.begin(), cumulativeLength_.end(), s);
    std::size_t i =
        static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - cumulativeLength_.begin()) - 1));
    i = std::min(i, vertices_.size() - 1);
    const double len = cumulativeLength_[i + 1] - cumulativeLength_[i];
    const double t = len > 0 ? (s - cumulativeLength_[i]) / len : 0.0;
    return vertex(i) + t * (vertex(i + 1) - vertex(i));
}

double Polygon::turnDeg(std::size_t i) const {
    const std::size_t n = vertices_.size();
    const Vec2 in = vertex(i) - vertex(i + n - 1), out = vertex(i + 1) - vertex(i);
    return std::atan2(cross(in, out), dot(in, out)) * 180.0 / M_PI;
}

Vec2 Polygon::outwardNormal(std::size_t edge) const {
    const Vec2 d = vertex(edge + 1) - vertex(edge);
    const double l = norm(d);
    return {d.y / l, -d.x / l};  // counter-clockwise outline: the outside is on the right
}

Polygon Polygon::transformed(double degrees, Vec2 offset) const {
    std::vector<Vec2> out;
    out.reserve(vertices_.size());
    for (Vec2 v : vertices_) out.push_back(rotated(v, degrees) + offset);
    return Polygon(std::move(out), MovedWhole{});
}

std::vector<Vec2> Polygon::offsetOutline(double d) const {
    const std::size_t n = vertices_.size();
    std::vector<Vec2> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t prev = (i + n - 1) % n;
        const Vec2 n0 = outwardNormal(prev), n1 = outwardNormal(i);
        const Vec2 p0 = vertex(prev) + d * n0, dir0 = vertex(i) - vertex(prev);
        const Vec2 p1 = vertex(i) + d * n1, dir1 = vertex(i + 1) - vertex(i);
        const double den = cross(dir0, dir1);
        if (std::abs(den) < 1e-12) {
            out.push_back(vertex(i) + d * n1);
        } else {
            const double t = cross(p1 - p0, dir1) / den;
            out.push_back(p0 + t * dir0);
        }
    }
    return out;
}

}  // namespace activetouch
