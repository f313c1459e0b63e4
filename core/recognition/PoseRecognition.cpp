#include "core/recognition/PoseRecognition.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

/// A capped distance grid of a polyline: each segment updates only the cells within the cap.
struct Grid {
    Vec2 origin;
    double cell = 1.0;  ///< mm; small enough to interpolate, and 12 grids stay in cache
    int nx = 0, ny = 0;
    std::vector<float> d;        ///< owned cells (a path's grid)
    const float* ptr = nullptr;  ///< the cells looked up: d's, or a template's

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
                for (int x = x0; x <= x1; ++x) {
                    const Vec2 p = origin + Vec2{x * cell, y * cell};
                    float& v = d[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) +
                                 static_cast<std::size_t>(x)];
                    v = std::min(v, static_cast<float>(segmentDistance(p, a, b)));
                }
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

/// Mean squared capped distance of `points` (world) mapped into the template frame by `pose`;
/// `coarse` looks up the nearest cell instead of interpolating.
double forwardCost(const Grid& grid, const std::vector<Vec2>& points, const Pose& pose,
                   bool coarse = false) {
    const double a = -pose.thetaDeg * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    double sum = 0.0;
    for (Vec2 p : points) {
        const Vec2 q = rotated(p - pose.t, c, s);
        const double d = coarse ? grid.nearest(q) : grid.at(q);
        sum += d * d;
    }
    return points.empty() ? 0.0 : sum / static_cast<double>(points.size());
}

/// Mean squared capped distance of the template's points, placed by `pose`, to the path.
double reverseCost(const std::vector<Vec2>& tplPoints, const Grid& pathGrid, const Pose& pose) {
    const double a = pose.thetaDeg * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    double sum = 0.0;
    for (Vec2 q : tplPoints) {
        const double d = pathGrid.at(rotated(q, c, s) + pose.t);
        sum += d * d;
    }
    return tplPoints.empty() ? 0.0 : sum / static_cast<double>(tplPoints.size());
}

/// Every other point: the search steers by half the points, the score counts them all.
std::vector<Vec2> halved(const std::vector<Vec2>& points) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < points.size(); i += 2) out.push_back(points[i]);
    return out;
}

Grid gridOf(const PoseTemplate& tpl) {
    Grid g;
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

PoseTemplate poseTemplate(const std::string& shape, const Polygon& outline, double offset_mm) {
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

double rotationErrorDeg(double a, double b, int symmetry) {
    if (symmetry == 0) return 0.0;
    const double period = 360.0 / std::max(1, symmetry);
    const double d = wrapDeg(a - b, period);
    return std::min(d, period - d);
}

PoseRecognition recognisePose(const std::vector<Vec2>& path,
                              const std::vector<PoseTemplate>& templates) {
    PoseRecognition out;
    std::vector<Vec2> finite;
    for (Vec2 p : path)
        if (std::isfinite(p.x) && std::isfinite(p.y)) finite.push_back(p);
    if (templates.empty() || finite.size() < 3) return out;
    const std::vector<Vec2> points = resampled(finite, kSpacing_mm, false);
    if (points.size() < 3) return out;
    const Vec2 centre = lengthCentroid(finite, false);
    std::vector<Vec2> coarse;
    const std::size_t stride = std::max<std::size_t>(1, points.size() / kCoarsePoints);
    for (std::size_t i = 0; i < points.size(); i += stride) coarse.push_back(points[i]);
    const std::vector<Vec2> searchPoints = halved(points);
    Grid pathGrid;
    pathGrid.cell = kPathCell_mm;
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
        grids.push_back(gridOf(templates[i]));
        std::vector<std::pair<double, double>> byTurn;  // cost, turn
        for (double th = 0.0; th < 360.0; th += kCoarseStepDeg)
            byTurn.push_back({forwardCost(grids.back(), coarse, {th, centre}, true), th});
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
        const std::vector<Vec2> tplSearch = halved(tpl.points);
        auto cost = [&](const Pose& p) {
            return 0.5 * (forwardCost(grid, searchPoints, p) + reverseCost(tplSearch, pathGrid, p));
        };
        auto fullCost = [&](const Pose& p) {
            return 0.5 * (forwardCost(grid, points, p) + reverseCost(tpl.points, pathGrid, p));
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

}  // namespace activetouch
