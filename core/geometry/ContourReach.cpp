#include "core/geometry/ContourReach.h"

#include <algorithm>
#include <cmath>

#include "core/common/RecentlyKept.h"

namespace activetouch {

namespace {

struct ContourSamples {
    std::vector<Vec2> points, normals;
};

ContourSamples sampleContour(const Polygon& outline, std::size_t n) {
    ContourSamples s;
    s.points.reserve(n);
    s.normals.reserve(n);
    const double perimeter = outline.perimeter();
    std::size_t edge = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double arc = static_cast<double>(i) * perimeter / static_cast<double>(n);
        auto edgeEnd = [&](std::size_t e) {
            return e + 1 < outline.size() ? outline.arcLengthOfVertex(e + 1) : perimeter;
        };
        while (edge + 1 < outline.size() && edgeEnd(edge) <= arc) ++edge;
        const Vec2 a = outline.vertex(edge), b = outline.vertex(edge + 1);
        const double length = edgeEnd(edge) - outline.arcLengthOfVertex(edge);
        const double t = std::clamp((arc - outline.arcLengthOfVertex(edge)) / length, 0.0, 1.0);
        s.points.push_back(a + t * (b - a));
        s.normals.push_back(outline.outwardNormal(edge));
    }
    return s;
}

double segmentDistance(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 ab = b - a;
    const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
    return distance(p, a + t * ab);
}

/// Whether a disc of radius r at c keeps clear of every edge of `outline` (touching allowed).
bool discClear(const Polygon& outline, Vec2 c, double r) {
    const double limit = r * (1.0 - 1e-7) - 1e-9;
    for (std::size_t e = 0; e < outline.size(); ++e) {
        const Vec2 a = outline.vertex(e), b = outline.vertex(e + 1);
        if (std::min(a.x, b.x) > c.x + r || std::max(a.x, b.x) < c.x - r ||
            std::min(a.y, b.y) > c.y + r || std::max(a.y, b.y) < c.y - r)
            continue;
        if (segmentDistance(c, a, b) < limit) return false;
    }
    return true;
}

/// For each sample, how far the nearest disc of radius r that touches the contour from one side
/// (`side` +1 outside, -1 on the object) without crossing it stays from the sample: 0 where one
/// touches it, at most `cap`.
std::vector<double> discGaps(const Polygon& outline, const ContourSamples& s, double r, double side,
                             double cap) {
    std::vector<Vec2> centres;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const Vec2 c = s.points[i] + (side * r) * s.normals[i];
        if (discClear(outline, c, r)) centres.push_back(c);
    }
    // Round a corner that turns away from the disc's side, the disc pivots on the vertex: its
    // centres sweep the arc between the two edges' normals, every 10 degrees at most.
    for (std::size_t v = 0; v < outline.size(); ++v) {
        const double turn = outline.turnDeg(v);
        if (side * turn <= 0.0) continue;
        const Vec2 from = side * outline.outwardNormal((v + outline.size() - 1) % outline.size());
        const int steps = static_cast<int>(std::ceil(std::abs(turn) / 10.0));
        for (int k = 1; k < steps; ++k) {
            const Vec2 c = outline.vertex(v) + r * rotated(from, turn * k / steps);
            if (discClear(outline, c, r)) centres.push_back(c);
        }
    }
    // A dense grid of the centres, cells at least r across, so a sample looks a few cells round.
    const Vec2 lo = outline.boundingBoxMin() - Vec2{r, r},
               hi = outline.boundingBoxMax() + Vec2{r, r};
    const double cell = std::max({r, (hi.x - lo.x) / 256.0, (hi.y - lo.y) / 256.0});
    const int nx = static_cast<int>((hi.x - lo.x) / cell) + 1;
    const int ny = static_cast<int>((hi.y - lo.y) / cell) + 1;
    std::vector<std::vector<Vec2>> grid(static_cast<std::size_t>(nx * ny));
    auto cellOf = [&](Vec2 p, int& ix, int& iy) {
        ix = std::clamp(static_cast<int>((p.x - lo.x) / cell), 0, nx - 1);
        iy = std::clamp(static_cast<int>((p.y - lo.y) / cell), 0, ny - 1);
    };
    for (Vec2 c : centres) {
        int ix, iy;
        cellOf(c, ix, iy);
        grid[static_cast<std::size_t>(iy * nx + ix)].push_back(c);
    }
    const int rings = static_cast<int>(std::ceil((r + cap) / cell));
    std::vector<double> gaps(s.points.size(), cap);
    for (std::size_t j = 0; j < s.points.size(); ++j) {
        int cx, cy;
        cellOf(s.points[j], cx, cy);
        double best = cap;
        for (int iy = std::max(0, cy - rings); iy <= std::min(ny - 1, cy + rings); ++iy)
            for (int ix = std::max(0, cx - rings); ix <= std::min(nx - 1, cx + rings); ++ix)
                for (Vec2 c : grid[static_cast<std::size_t>(iy * nx + ix)])
                    best = std::min(best, std::max(0.0, distance(s.points[j], c) - r));
        gaps[j] = best;
    }
    return gaps;
}

}  // namespace

std::size_t ContourReach::sampleCount(double perimeter_mm) {
    const double n = std::ceil(perimeter_mm / kStep_mm);
    return n < 1.0 ? 1 : std::min(kMaxSamples, static_cast<std::size_t>(n));
}

ContourReach::ContourReach(const Polygon& outline, double radius_mm)
    : radius_(std::max(0.0, radius_mm)) {
    const std::size_t n = sampleCount(outline.perimeter());
    reachable_.assign(n, 1);
    if (!(radius_ > 0.0) || outline.size() < 3) return;
    const ContourSamples s = sampleContour(outline, n);
    const double cap = 2.0 * radius_;
    const std::vector<double> inward = discGaps(outline, s, radius_, +1.0, cap);
    const std::vector<double> outward = discGaps(outline, s, radius_, -1.0, cap);
    for (std::size_t i = 0; i < n; ++i)
        reachable_[i] = inward[i] <= tolerance_mm() && outward[i] <= tolerance_mm();
    collectStretches(outline, s.points, inward, outward);
}

std::shared_ptr<const ContourReach> ContourReach::shared(const Polygon& outline, double radius_mm) {
    static RecentlyKept<std::pair<std::vector<Vec2>, double>, ContourReach, 32> kept;
    return kept.get({outline.vertices(), radius_mm},
                    [&] { return std::make_shared<const ContourReach>(outline, radius_mm); });
}

double ContourReach::reachableFraction() const {
    const auto n = std::count(reachable_.begin(), reachable_.end(), char(1));
    return static_cast<double>(n) / static_cast<double>(reachable_.size());
}

void ContourReach::collectStretches(const Polygon& outline, const std::vector<Vec2>& points,
                                    const std::vector<double>& inwardGap,
                                    const std::vector<double>& outwardGap) {
    const std::size_t n = points.size();
    // -1 within reach, else the kind that fails most there.
    auto label = [&](std::size_t i) {
        if (reachable_[i % n]) return -1;
        return inwardGap[i % n] >= outwardGap[i % n] ? int(OutOfReach::Kind::Inward)
                                                     : int(OutOfReach::Kind::Outward);
    };
    std::size_t start = 0;
    while (start < n && label(start) == label(start + n - 1)) ++start;
    if (start == n) {  // one label all round
        if (label(0) == -1) return;
        start = 0;
    }
    const double step = outline.perimeter() / static_cast<double>(n);
    const double cap = 2.0 * radius_;
    for (std::size_t done = 0; done < n;) {
        const std::size_t first = start + done;
        const int kind = label(first);
        std::size_t count = 1;
        while (done + count < n && label(first + count) == kind) ++count;
        done += count;
        if (kind < 0) continue;
        OutOfReach o;
        o.kind = static_cast<OutOfReach::Kind>(kind);
        o.fromArc_mm = static_cast<double>(first % n) * step;
        o.length_mm = static_cast<double>(count) * step;
        o.mouth_mm = distance(points[first % n], points[(first + count - 1) % n]);
        o.middle = points[(first + count / 2) % n];
        const std::vector<double>& gap =
            o.kind == OutOfReach::Kind::Inward ? inwardGap : outwardGap;
        for (std::size_t k = 0; k < count; ++k)
            o.depth_mm = std::max(o.depth_mm, gap[(first + k) % n]);
        o.depthCapped = o.depth_mm >= cap * (1.0 - 1e-9);
        stretches_.push_back(o);
    }
    std::sort(stretches_.begin(), stretches_.end(),
              [](const OutOfReach& a, const OutOfReach& b) { return a.fromArc_mm < b.fromArc_mm; });
}

}  // namespace activetouch
