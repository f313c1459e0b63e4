#pragma once
// The distance grids a pose search fits a path to (PoseRecognition.cpp): an outline's or a path's
// capped distance field on a regular grid, looked up bilinearly or at the nearest cell, and the
// sum of squared distances of points mapped onto it, portable and in vector lanes. Internal to
// core/recognition.
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "core/recognition/PoseRecognition.h"

namespace activetouch::posegrid {

inline constexpr double kPi = 3.14159265358979323846;

/// Distances are capped here, mm: beyond it a point counts as simply off the outline.
inline constexpr double kCap_mm = 5.0;

inline constexpr double kSpacing_mm = 2.0;  ///< resampling along outlines and paths (a follow step)

inline constexpr double kCoarseStepDeg = 6.0;

inline constexpr std::size_t kCoarsePoints = 24;

inline constexpr std::size_t kRefinedTemplates = 3;

inline constexpr double kPathCell_mm = 1.0;  ///< the path's own grid, built for every path

Vec2 rotated(Vec2 v, double c, double s);

/// Points every `spacing` along a polyline (closed: back to the first point too).
std::vector<Vec2> resampled(const std::vector<Vec2>& line, double spacing, bool closed);

/// The centroid of a polyline's length.
Vec2 lengthCentroid(const std::vector<Vec2>& line, bool closed);

double segmentDistance(Vec2 p, Vec2 a, Vec2 b);

/// row[x] = min(row[x], segmentDistance() of the cell), one cell.
void nearerCell(float* row, int x, double ox, double y, double cell, Vec2 a, Vec2 b);

/// row[x] = min(row[x], distance from (ox + x * cell, y) to segment ab) for x0 <= x <= x1, each
/// cell as segmentDistance() gives it: four cells at a time where the CPU has AVX2, by the same
/// operations (no fused multiply-adds), so that the grid is bit for bit the same.
#if defined(__x86_64__)
__attribute__((target("avx2"))) void nearerAlongRowAvx2(float* row, int x0, int x1, double ox,
                                                        double y, double cell, Vec2 a, Vec2 b);

#endif

void nearerAlongRow(float* row, int x0, int x1, double ox, double y, double cell, Vec2 a, Vec2 b,
                    bool portable);

/// A capped distance grid of a polyline: each segment updates only the cells within the cap.
struct Grid {
    Vec2 origin;
    double cell = 1.0;  ///< mm; small enough to interpolate, and 12 grids stay in cache
    int nx = 0, ny = 0;
    std::vector<float> d;        ///< owned cells (a path's grid)
    const float* ptr = nullptr;  ///< the cells looked up: d's, or a template's
    bool portable = false;       ///< built and read without the vector units (a test's reference)

    void build(const std::vector<Vec2>& line, bool closed) {
        Vec2 lo = line.front(), hi = lo;
        for (Vec2 p : line) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
        }
        const double margin = kCap_mm + 2 * cell;
        origin = lo - Vec2{margin, margin};
        nx = static_cast<int>(std::ceil((hi.x - lo.x + 2 * margin) / cell)) + 1;
        ny = static_cast<int>(std::ceil((hi.y - lo.y + 2 * margin) / cell)) + 1;
        d.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), float(kCap_mm));
        const std::size_t segments = closed ? line.size() : line.size() - 1;
        const int reach = static_cast<int>(std::ceil(kCap_mm / cell)) + 1;
        for (std::size_t i = 0; i < std::max<std::size_t>(segments, 1); ++i) {
            const Vec2 a = line[i], b = line[(i + 1) % line.size()];
            const int x0 =
                std::max(0, static_cast<int>((std::min(a.x, b.x) - origin.x) / cell) - reach);
            const int x1 =
                std::min(nx - 1, static_cast<int>((std::max(a.x, b.x) - origin.x) / cell) + reach);
            const int y0 =
                std::max(0, static_cast<int>((std::min(a.y, b.y) - origin.y) / cell) - reach);
            const int y1 =
                std::min(ny - 1, static_cast<int>((std::max(a.y, b.y) - origin.y) / cell) + reach);
            for (int y = y0; y <= y1; ++y)
                nearerAlongRow(
                    d.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(nx), x0, x1,
                    origin.x, origin.y + y * cell, cell, a, b, portable);
        }
        ptr = d.data();
    }

    /// The distance of the cell nearest `p`, the cap outside the grid: the coarse search's.
    double nearest(Vec2 p) const {
        const double fx = (p.x - origin.x) * (1.0 / cell) + 0.5,
                     fy = (p.y - origin.y) * (1.0 / cell) + 0.5;
        if (!(fx >= 0.0) || !(fy >= 0.0) || fx >= nx || fy >= ny) return kCap_mm;
        return ptr[static_cast<std::size_t>(fy) * static_cast<std::size_t>(nx) +
                   static_cast<std::size_t>(fx)];
    }

    /// Bilinear distance at `p`, the cap outside the grid.
    double at(Vec2 p) const {
        const double fx = (p.x - origin.x) * (1.0 / cell), fy = (p.y - origin.y) * (1.0 / cell);
        if (!(fx >= 0.0) || !(fy >= 0.0) || fx >= nx - 1 || fy >= ny - 1) return kCap_mm;
        const int x = static_cast<int>(fx), y = static_cast<int>(fy);
        const double u = fx - x, v = fy - y;
        const float* row = ptr + static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) +
                           static_cast<std::size_t>(x);
        return (1 - v) * ((1 - u) * row[0] + u * row[1]) +
               v * ((1 - u) * row[nx] + u * row[nx + 1]);
    }
};

struct Pose {
    double thetaDeg = 0.0;
    Vec2 t;
};

/// Points as two arrays, x and y, for the vector lookups.
struct Coords {
    std::vector<double> x, y;
    explicit Coords(const std::vector<Vec2>& points) {
        x.reserve(points.size());
        y.reserve(points.size());
        for (Vec2 p : points) {
            x.push_back(p.x);
            y.push_back(p.y);
        }
    }
    std::size_t size() const { return x.size(); }
};

/// How a cost maps its points onto the grid it looks up: into a template's frame (q = R(p - t),
/// R turning by -theta) or out of it onto the path (q = R p + t, R turning by +theta).
enum class Mapping { IntoFrame, OntoPath };

Vec2 mapped(Vec2 p, double c, double s, Vec2 t, Mapping m);

/// How a cost reads the grid: bilinear (Grid::at) or the nearest cell (Grid::nearest).
enum class Lookup { Bilinear, Nearest };

double lookedUp(const Grid& grid, Vec2 q, Lookup l);

/// `sum` plus the squared capped distances of the mapped points from..to - 1, added in their
/// order.
double sumSquaredPortable(const Grid& grid, const Coords& pts, std::size_t from, std::size_t to,
                          double c, double s, Vec2 t, Mapping m, Lookup l, double sum);

/// The same, four points at a time: the same operations on each point as Grid::at and
/// Grid::nearest (no fused multiply-adds), the cells gathered, and the squares added one by one
/// in order, so that the sum is bit for bit the portable one.
#if defined(__x86_64__)
__attribute__((target("avx2"))) double sumSquaredAvx2(const Grid& grid, const Coords& pts,
                                                      std::size_t from, std::size_t to, double c,
                                                      double s, Vec2 t, Mapping m, Lookup l,
                                                      double sum);

#endif

double sumSquared(const Grid& grid, const Coords& pts, std::size_t from, std::size_t to, double c,
                  double s, Vec2 t, Mapping m, Lookup l, double sum);

/// Mean squared capped distance of `points` mapped by `pose`: world points into a template's
/// frame (IntoFrame, turning by -theta), or a template's points onto the path (OntoPath, by
/// +theta). With a `limit`: +infinity as soon as `before` plus the mean so far reaches it, the
/// rest unread (squares only add: the whole mean would reach it too); otherwise the same bits as
/// without one.
double meanCost(const Grid& grid, const Coords& points, const Pose& pose, Mapping m, Lookup l,
                double before = 0.0, double limit = std::numeric_limits<double>::infinity());

/// Every other point: the search steers by half the points, the score counts them all.
std::vector<Vec2> halved(const std::vector<Vec2>& points);

Grid gridOf(const PoseTemplate& tpl, bool portable);

double wrapDeg(double a, double period);

}  // namespace activetouch::posegrid
