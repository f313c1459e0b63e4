#include "core/recognition/PoseRecognition.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/common/Avx2Clones.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace activetouch {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Distances are capped here, mm: beyond it a point counts as simply off the outline.
constexpr double kCap_mm = 5.0;
constexpr double kSpacing_mm = 2.0;  ///< resampling along outlines and paths (a follow step)
constexpr double kCoarseStepDeg = 6.0;
constexpr std::size_t kCoarsePoints = 24;
constexpr std::size_t kRefinedTemplates = 3;
constexpr double kPathCell_mm = 1.0;  ///< the path's own grid, built for every path

Vec2 rotated(Vec2 v, double c, double s) {
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

/// Points every `spacing` along a polyline (closed: back to the first point too).
std::vector<Vec2> resampled(const std::vector<Vec2>& line, double spacing, bool closed) {
    std::vector<Vec2> out;
    if (line.empty()) return out;
    out.push_back(line.front());
    double carried = 0.0;  // length since the last point put out
    const std::size_t segments = closed ? line.size() : line.size() - 1;
    for (std::size_t i = 0; i < segments; ++i) {
        const Vec2 a = line[i], b = line[(i + 1) % line.size()];
        const double len = distance(a, b);
        if (len <= 0.0) continue;
        double at = spacing - carried;
        while (at <= len) {
            out.push_back(a + (at / len) * (b - a));
            at += spacing;
        }
        carried = len - (at - spacing);
    }
    if (closed && out.size() > 1 && distance(out.back(), out.front()) < 0.5 * spacing)
        out.pop_back();
    return out;
}

/// The centroid of a polyline's length.
Vec2 lengthCentroid(const std::vector<Vec2>& line, bool closed) {
    Vec2 sum{};
    double total = 0.0;
    const std::size_t segments = closed ? line.size() : line.size() - 1;
    for (std::size_t i = 0; i < segments; ++i) {
        const Vec2 a = line[i], b = line[(i + 1) % line.size()];
        const double len = distance(a, b);
        sum = sum + (0.5 * len) * (a + b);
        total += len;
    }
    if (total <= 0.0) {
        for (Vec2 p : line) sum = sum + p;
        return (1.0 / static_cast<double>(line.size())) * sum;
    }
    return (1.0 / total) * sum;
}

double segmentDistance(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 ab = b - a;
    const double len2 = dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return distance(p, a + t * ab);
}

/// row[x] = min(row[x], segmentDistance() of the cell), one cell.
void nearerCell(float* row, int x, double ox, double y, double cell, Vec2 a, Vec2 b) {
    row[x] = std::min(row[x], static_cast<float>(segmentDistance({ox + x * cell, y}, a, b)));
}

/// row[x] = min(row[x], distance from (ox + x * cell, y) to segment ab) for x0 <= x <= x1, each
/// cell as segmentDistance() gives it: four cells at a time where the CPU has AVX2, by the same
/// operations (no fused multiply-adds), so that the grid is bit for bit the same.
#if defined(__x86_64__)
__attribute__((target("avx2"))) void nearerAlongRowAvx2(float* row, int x0, int x1, double ox,
                                                        double y, double cell, Vec2 a, Vec2 b) {
    const double abx = b.x - a.x, aby = b.y - a.y;
    const double len2 = abx * abx + aby * aby;
    const __m256d vox = _mm256_set1_pd(ox), vcell = _mm256_set1_pd(cell);
    const __m256d ax = _mm256_set1_pd(a.x), ay = _mm256_set1_pd(a.y), vy = _mm256_set1_pd(y);
    const __m256d vabx = _mm256_set1_pd(abx), vaby = _mm256_set1_pd(aby);
    const __m256d alongY = _mm256_set1_pd((y - a.y) * aby), vlen2 = _mm256_set1_pd(len2);
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
    int x = x0;
    for (; x + 3 <= x1; x += 4) {
        const __m256d px =
            _mm256_add_pd(vox, _mm256_mul_pd(_mm256_cvtepi32_pd(_mm_add_epi32(
                                                 _mm_set1_epi32(x), _mm_setr_epi32(0, 1, 2, 3))),
                                             vcell));
        __m256d t = zero;
        if (len2 > 0.0) {
            t = _mm256_div_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_sub_pd(px, ax), vabx), alongY),
                              vlen2);
            // std::clamp: below 0 gives 0, above 1 gives 1, anything else itself.
            t = _mm256_blendv_pd(t, zero, _mm256_cmp_pd(t, zero, _CMP_LT_OQ));
            t = _mm256_blendv_pd(t, one, _mm256_cmp_pd(one, t, _CMP_LT_OQ));
        }
        const __m256d dx = _mm256_sub_pd(px, _mm256_add_pd(ax, _mm256_mul_pd(t, vabx)));
        const __m256d dy = _mm256_sub_pd(vy, _mm256_add_pd(ay, _mm256_mul_pd(t, vaby)));
        const __m128 dist = _mm256_cvtpd_ps(
            _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy))));
        // std::min(row, dist): dist where it is smaller, else row.
        _mm_storeu_ps(row + x, _mm_min_ps(dist, _mm_loadu_ps(row + x)));
    }
    for (; x <= x1; ++x) nearerCell(row, x, ox, y, cell, a, b);
}
#endif

void nearerAlongRow(float* row, int x0, int x1, double ox, double y, double cell, Vec2 a, Vec2 b,
                    bool portable) {
#if defined(__x86_64__)
    if (!portable && cpuHasAvx2()) return nearerAlongRowAvx2(row, x0, x1, ox, y, cell, a, b);
#endif
    for (int x = x0; x <= x1; ++x) nearerCell(row, x, ox, y, cell, a, b);
}

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

Vec2 mapped(Vec2 p, double c, double s, Vec2 t, Mapping m) {
    return m == Mapping::IntoFrame ? rotated(p - t, c, s) : rotated(p, c, s) + t;
}

/// How a cost reads the grid: bilinear (Grid::at) or the nearest cell (Grid::nearest).
enum class Lookup { Bilinear, Nearest };

double lookedUp(const Grid& grid, Vec2 q, Lookup l) {
    return l == Lookup::Bilinear ? grid.at(q) : grid.nearest(q);
}

/// Sum of the squared capped distances of the mapped points, added in their order.
double sumSquaredPortable(const Grid& grid, const Coords& pts, double c, double s, Vec2 t,
                          Mapping m, Lookup l) {
    double sum = 0.0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const double d = lookedUp(grid, mapped({pts.x[i], pts.y[i]}, c, s, t, m), l);
        sum += d * d;
    }
    return sum;
}

#if defined(__x86_64__)
/// The same, four points at a time: the same operations on each point as Grid::at and
/// Grid::nearest (no fused multiply-adds), the cells gathered, and the squares added one by one
/// in order, so that the sum is bit for bit the portable one.
__attribute__((target("avx2"))) double sumSquaredAvx2(const Grid& grid, const Coords& pts, double c,
                                                      double s, Vec2 t, Mapping m, Lookup l) {
    const std::size_t n = pts.size(), whole = n / 4 * 4;
    const __m256d vc = _mm256_set1_pd(c), vs = _mm256_set1_pd(s);
    const __m256d tx = _mm256_set1_pd(t.x), ty = _mm256_set1_pd(t.y);
    const __m256d ox = _mm256_set1_pd(grid.origin.x), oy = _mm256_set1_pd(grid.origin.y);
    const __m256d inv = _mm256_set1_pd(1.0 / grid.cell), zero = _mm256_setzero_pd();
    const __m256d one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
    const __m256d cap = _mm256_set1_pd(kCap_mm);
    // Interpolation reads the next cell too, so it stops a cell before the grid's end.
    const int reach = l == Lookup::Bilinear ? 1 : 0;
    const __m256d xEnd = _mm256_set1_pd(grid.nx - reach), yEnd = _mm256_set1_pd(grid.ny - reach);
    const __m128i stride = _mm_set1_epi32(grid.nx), right = _mm_set1_epi32(1);
    const float* cells = grid.ptr;
    double sum = 0.0;
    alignas(32) double squares[4];
    for (std::size_t i = 0; i < whole; i += 4) {
        const __m256d px = _mm256_loadu_pd(pts.x.data() + i);
        const __m256d py = _mm256_loadu_pd(pts.y.data() + i);
        __m256d qx, qy;
        if (m == Mapping::IntoFrame) {
            const __m256d vx = _mm256_sub_pd(px, tx), vy = _mm256_sub_pd(py, ty);
            qx = _mm256_sub_pd(_mm256_mul_pd(vc, vx), _mm256_mul_pd(vs, vy));
            qy = _mm256_add_pd(_mm256_mul_pd(vs, vx), _mm256_mul_pd(vc, vy));
        } else {
            qx = _mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(vc, px), _mm256_mul_pd(vs, py)), tx);
            qy = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(vs, px), _mm256_mul_pd(vc, py)), ty);
        }
        __m256d fx = _mm256_mul_pd(_mm256_sub_pd(qx, ox), inv);
        __m256d fy = _mm256_mul_pd(_mm256_sub_pd(qy, oy), inv);
        if (l == Lookup::Nearest) {
            fx = _mm256_add_pd(fx, half);
            fy = _mm256_add_pd(fy, half);
        }
        // Inside where the lookup reads the grid (ordered compares: NaN is outside); elsewhere
        // the cap, with the lookups moved to cell 0 so that they stay in the grid.
        const __m256d inside = _mm256_and_pd(
            _mm256_and_pd(_mm256_cmp_pd(fx, zero, _CMP_GE_OQ), _mm256_cmp_pd(fy, zero, _CMP_GE_OQ)),
            _mm256_and_pd(_mm256_cmp_pd(fx, xEnd, _CMP_LT_OQ),
                          _mm256_cmp_pd(fy, yEnd, _CMP_LT_OQ)));
        const __m256d gx = _mm256_and_pd(inside, fx), gy = _mm256_and_pd(inside, fy);
        const __m128i xi = _mm256_cvttpd_epi32(gx), yi = _mm256_cvttpd_epi32(gy);
        const __m128i at = _mm_add_epi32(_mm_mullo_epi32(yi, stride), xi);
        __m256d d;
        if (l == Lookup::Nearest) {
            d = _mm256_blendv_pd(cap, _mm256_cvtps_pd(_mm_i32gather_ps(cells, at, 4)), inside);
        } else {
            const __m256d u = _mm256_sub_pd(gx, _mm256_cvtepi32_pd(xi));
            const __m256d v = _mm256_sub_pd(gy, _mm256_cvtepi32_pd(yi));
            const __m128i below = _mm_add_epi32(at, stride);
            const __m256d r0 = _mm256_cvtps_pd(_mm_i32gather_ps(cells, at, 4));
            const __m256d r1 =
                _mm256_cvtps_pd(_mm_i32gather_ps(cells, _mm_add_epi32(at, right), 4));
            const __m256d r2 = _mm256_cvtps_pd(_mm_i32gather_ps(cells, below, 4));
            const __m256d r3 =
                _mm256_cvtps_pd(_mm_i32gather_ps(cells, _mm_add_epi32(below, right), 4));
            const __m256d nu = _mm256_sub_pd(one, u), nv = _mm256_sub_pd(one, v);
            const __m256d top = _mm256_add_pd(_mm256_mul_pd(nu, r0), _mm256_mul_pd(u, r1));
            const __m256d bottom = _mm256_add_pd(_mm256_mul_pd(nu, r2), _mm256_mul_pd(u, r3));
            const __m256d value = _mm256_add_pd(_mm256_mul_pd(nv, top), _mm256_mul_pd(v, bottom));
            d = _mm256_blendv_pd(cap, value, inside);
        }
        _mm256_store_pd(squares, _mm256_mul_pd(d, d));
        sum += squares[0];
        sum += squares[1];
        sum += squares[2];
        sum += squares[3];
    }
    for (std::size_t i = whole; i < n; ++i) {
        const double d = lookedUp(grid, mapped({pts.x[i], pts.y[i]}, c, s, t, m), l);
        sum += d * d;
    }
    return sum;
}
#endif

double sumSquared(const Grid& grid, const Coords& pts, double c, double s, Vec2 t, Mapping m,
                  Lookup l) {
#if defined(__x86_64__)
    if (!grid.portable && cpuHasAvx2()) return sumSquaredAvx2(grid, pts, c, s, t, m, l);
#endif
    return sumSquaredPortable(grid, pts, c, s, t, m, l);
}

/// Mean squared capped distance of `points` mapped by `pose`: world points into a template's
/// frame (IntoFrame, turning by -theta), or a template's points onto the path (OntoPath, by
/// +theta).
double meanCost(const Grid& grid, const Coords& points, const Pose& pose, Mapping m, Lookup l) {
    const double turn = m == Mapping::IntoFrame ? -pose.thetaDeg : pose.thetaDeg;
    const double a = turn * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    const double sum = sumSquared(grid, points, c, s, pose.t, m, l);
    return points.size() == 0 ? 0.0 : sum / static_cast<double>(points.size());
}

/// Every other point: the search steers by half the points, the score counts them all.
std::vector<Vec2> halved(const std::vector<Vec2>& points) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < points.size(); i += 2) out.push_back(points[i]);
    return out;
}

Grid gridOf(const PoseTemplate& tpl, bool portable) {
    Grid g;
    g.portable = portable;
    g.origin = tpl.gridOrigin;
    g.cell = tpl.cell_mm;
    g.nx = tpl.nx;
    g.ny = tpl.ny;
    g.ptr = tpl.distance.data();
    return g;
}

double wrapDeg(double a, double period) {
    a = std::fmod(a, period);
    return a < 0 ? a + period : a;
}

}  // namespace

namespace detail {

PoseTemplate poseTemplate(const std::string& shape, const Polygon& outline, double offset_mm,
                          bool portable) {
    PoseTemplate tpl;
    tpl.shape = shape;
    std::vector<Vec2> line =
        std::abs(offset_mm) > 1e-9 ? outline.offsetOutline(offset_mm) : outline.vertices();
    tpl.centroid = lengthCentroid(line, true);
    for (Vec2& p : line) p = p - tpl.centroid;
    tpl.points = resampled(line, kSpacing_mm, true);
    tpl.perimeter_mm = 0.0;
    for (std::size_t i = 0; i < line.size(); ++i)
        tpl.perimeter_mm += distance(line[i], line[(i + 1) % line.size()]);
    Grid g;
    g.portable = portable;
    g.build(line, true);
    tpl.gridOrigin = g.origin;
    tpl.cell_mm = g.cell;
    tpl.nx = g.nx;
    tpl.ny = g.ny;
    // Symmetry: the largest k up to 12 for which a turn by 360 / k lays the outline on itself
    // (within a quarter millimetre); 12 means a circle to the fingertip.
    tpl.symmetry = 1;
    for (int k = 12; k >= 2; --k) {
        const double a = 2 * kPi / k, c = std::cos(a), s = std::sin(a);
        double sum = 0.0;
        for (Vec2 q : tpl.points) {  // exact distances: once per template, not per path
            const Vec2 r = rotated(q, c, s);
            double d = std::numeric_limits<double>::infinity();
            for (std::size_t j = 0; j < line.size(); ++j)
                d = std::min(d, segmentDistance(r, line[j], line[(j + 1) % line.size()]));
            sum += d * d;
        }
        if (std::sqrt(sum / static_cast<double>(tpl.points.size())) < 0.25) {
            tpl.symmetry = k == 12 ? 0 : k;
            break;
        }
    }
    tpl.distance = std::move(g.d);
    return tpl;
}

}  // namespace detail

double rotationErrorDeg(double a, double b, int symmetry) {
    if (symmetry == 0) return 0.0;
    const double period = 360.0 / std::max(1, symmetry);
    const double d = wrapDeg(a - b, period);
    return std::min(d, period - d);
}

namespace detail {

PoseRecognition recognisePose(const std::vector<Vec2>& path,
                              const std::vector<PoseTemplate>& templates, bool portable) {
    PoseRecognition out;
    std::vector<Vec2> finite;
    for (Vec2 p : path)
        if (std::isfinite(p.x) && std::isfinite(p.y)) finite.push_back(p);
    if (templates.empty() || finite.size() < 3) return out;
    const std::vector<Vec2> points = resampled(finite, kSpacing_mm, false);
    if (points.size() < 3) return out;
    const Vec2 centre = lengthCentroid(finite, false);
    std::vector<Vec2> coarsePoints;
    const std::size_t stride = std::max<std::size_t>(1, points.size() / kCoarsePoints);
    for (std::size_t i = 0; i < points.size(); i += stride) coarsePoints.push_back(points[i]);
    const Coords coarse(coarsePoints);
    const Coords searchPoints(halved(points)), allPoints(points);
    Grid pathGrid;
    pathGrid.cell = kPathCell_mm;
    pathGrid.portable = portable;
    pathGrid.build(finite, false);

    // Coarse: every template at every 6 degrees, placed on the path's centroid; the two best
    // turns at least 15 degrees apart go on to be refined.
    struct Candidate {
        std::size_t tpl;
        Pose pose[2];
        double coarse = 0.0, coarseSecond = 0.0;
    };
    std::vector<Candidate> candidates;
    std::vector<Grid> grids;
    grids.reserve(templates.size());
    for (std::size_t i = 0; i < templates.size(); ++i) {
        grids.push_back(gridOf(templates[i], portable));
        std::vector<std::pair<double, double>> byTurn;  // cost, turn
        for (double th = 0.0; th < 360.0; th += kCoarseStepDeg)
            byTurn.push_back(
                {meanCost(grids.back(), coarse, {th, centre}, Mapping::IntoFrame, Lookup::Nearest),
                 th});
        std::sort(byTurn.begin(), byTurn.end());
        Candidate c{i,
                    {{byTurn[0].second, centre}, {byTurn[0].second, centre}},
                    byTurn[0].first,
                    std::numeric_limits<double>::infinity()};
        for (const auto& [cost, th] : byTurn)
            if (rotationErrorDeg(th, byTurn[0].second, 1) > 15.0) {
                c.pose[1] = {th, centre};
                c.coarseSecond = cost;
                break;
            }
        candidates.push_back(c);
    }
    std::vector<std::size_t> order(candidates.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return candidates[a].coarse < candidates[b].coarse;
    });

    out.fits.resize(templates.size());
    for (std::size_t i = 0; i < templates.size(); ++i) {
        const PoseTemplate& tpl = templates[i];
        out.fits[i].shape = tpl.shape;
        out.fits[i].symmetry = tpl.symmetry;
        out.fits[i].score_mm = std::sqrt(candidates[i].coarse);
        const double turn = candidates[i].pose[0].thetaDeg;
        out.fits[i].rotationDeg = tpl.symmetry == 0 ? 0.0 : wrapDeg(turn, 360.0 / tpl.symmetry);
        out.fits[i].position = centre;
    }
    // Refined: the most promising templates, both turns, turn and place together by a pattern
    // search on the two-way cost.
    double bestScore = std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < std::min(kRefinedTemplates, order.size()); ++r) {
        const std::size_t i = order[r];
        const PoseTemplate& tpl = templates[i];
        const Grid& grid = grids[i];
        const Coords tplSearch(halved(tpl.points)), tplAll(tpl.points);
        auto cost = [&](const Pose& p) {
            return 0.5 * (meanCost(grid, searchPoints, p, Mapping::IntoFrame, Lookup::Bilinear) +
                          meanCost(pathGrid, tplSearch, p, Mapping::OntoPath, Lookup::Bilinear));
        };
        auto fullCost = [&](const Pose& p) {
            return 0.5 * (meanCost(grid, allPoints, p, Mapping::IntoFrame, Lookup::Bilinear) +
                          meanCost(pathGrid, tplAll, p, Mapping::OntoPath, Lookup::Bilinear));
        };
        double fitCost = std::numeric_limits<double>::infinity();
        Pose fitPose;
        for (int k = 0; k < 2; ++k) {
            // The second turn only where the coarse search found it nearly as good.
            if (k == 1 && !(candidates[i].coarseSecond < 1.5 * candidates[i].coarse)) break;
            Pose p = candidates[i].pose[k];
            double c = cost(p);
            double stepDeg = 2.0, stepMm = 0.8;
            while (stepDeg > 0.2) {
                bool moved = false;
                const Pose tries[6] = {
                    {p.thetaDeg + stepDeg, p.t},         {p.thetaDeg - stepDeg, p.t},
                    {p.thetaDeg, p.t + Vec2{stepMm, 0}}, {p.thetaDeg, p.t - Vec2{stepMm, 0}},
                    {p.thetaDeg, p.t + Vec2{0, stepMm}}, {p.thetaDeg, p.t - Vec2{0, stepMm}}};
                for (const Pose& q : tries) {
                    const double cq = cost(q);
                    if (cq < c) {
                        c = cq;
                        p = q;
                        moved = true;
                    }
                }
                if (!moved) {
                    stepDeg *= 0.5;
                    stepMm *= 0.5;
                }
            }
            if (const double full = fullCost(p); full < fitCost) {
                fitCost = full;
                fitPose = p;
            }
        }
        PoseFit& fit = out.fits[i];
        fit.score_mm = std::sqrt(fitCost);
        fit.position = fitPose.t;
        fit.rotationDeg = tpl.symmetry == 0 ? 0.0 : wrapDeg(fitPose.thetaDeg, 360.0 / tpl.symmetry);
        if (fit.score_mm < bestScore) {
            bestScore = fit.score_mm;
            out.best = fit;
        }
    }
    out.valid = true;
    out.predicted = out.best.shape;
    return out;
}

}  // namespace detail

PoseTemplate poseTemplate(const std::string& shape, const Polygon& outline, double offset_mm) {
    return detail::poseTemplate(shape, outline, offset_mm, false);
}

PoseRecognition recognisePose(const std::vector<Vec2>& path,
                              const std::vector<PoseTemplate>& templates) {
    return detail::recognisePose(path, templates, false);
}

}  // namespace activetouch
