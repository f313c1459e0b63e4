#include "core/recognition/PoseGrid.h"

#include <algorithm>

#include "core/common/Avx2Clones.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace activetouch::posegrid {

Vec2 rotated(Vec2 v, double c, double s) {
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

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

void nearerCell(float* row, int x, double ox, double y, double cell, Vec2 a, Vec2 b) {
    row[x] = std::min(row[x], static_cast<float>(segmentDistance({ox + x * cell, y}, a, b)));
}

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

Vec2 mapped(Vec2 p, double c, double s, Vec2 t, Mapping m) {
    return m == Mapping::IntoFrame ? rotated(p - t, c, s) : rotated(p, c, s) + t;
}

double lookedUp(const Grid& grid, Vec2 q, Lookup l) {
    return l == Lookup::Bilinear ? grid.at(q) : grid.nearest(q);
}

double sumSquaredPortable(const Grid& grid, const Coords& pts, std::size_t from, std::size_t to,
                          double c, double s, Vec2 t, Mapping m, Lookup l, double sum) {
    for (std::size_t i = from; i < to; ++i) {
        const double d = lookedUp(grid, mapped({pts.x[i], pts.y[i]}, c, s, t, m), l);
        sum += d * d;
    }
    return sum;
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) double sumSquaredAvx2(const Grid& grid, const Coords& pts,
                                                      std::size_t from, std::size_t to, double c,
                                                      double s, Vec2 t, Mapping m, Lookup l,
                                                      double sum) {
    const std::size_t whole = from + (to - from) / 4 * 4;
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
    alignas(32) double squares[4];
    for (std::size_t i = from; i < whole; i += 4) {
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
    for (std::size_t i = whole; i < to; ++i) {
        const double d = lookedUp(grid, mapped({pts.x[i], pts.y[i]}, c, s, t, m), l);
        sum += d * d;
    }
    return sum;
}

#endif

double sumSquared(const Grid& grid, const Coords& pts, std::size_t from, std::size_t to, double c,
                  double s, Vec2 t, Mapping m, Lookup l, double sum) {
#if defined(__x86_64__)
    if (!grid.portable && cpuHasAvx2())
        return sumSquaredAvx2(grid, pts, from, to, c, s, t, m, l, sum);
#endif
    return sumSquaredPortable(grid, pts, from, to, c, s, t, m, l, sum);
}

double meanCost(const Grid& grid, const Coords& points, const Pose& pose, Mapping m, Lookup l,
                double before, double limit) {
    const double turn = m == Mapping::IntoFrame ? -pose.thetaDeg : pose.thetaDeg;
    const double a = turn * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    const std::size_t n = points.size();
    if (n == 0) return 0.0;
    const double count = static_cast<double>(n);
    // In runs of a multiple of four points: the squares are added in the same order as in one
    // pass. Rounding is monotone, so a partial mean that reaches the limit decides.
    constexpr std::size_t kRun = 32;
    double sum = 0.0;
    for (std::size_t from = 0; from < n; from += kRun) {
        sum = sumSquared(grid, points, from, std::min(n, from + kRun), c, s, pose.t, m, l, sum);
        if (before + sum / count >= limit) return std::numeric_limits<double>::infinity();
    }
    return sum / count;
}

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

}  // namespace activetouch::posegrid
