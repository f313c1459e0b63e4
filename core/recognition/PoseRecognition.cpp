#include "core/recognition/PoseRecognition.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/recognition/PoseGrid.h"

namespace activetouch {

using namespace posegrid;

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

namespace {

/// A template's two best turns from the coarse search, at least 15 degrees apart.
struct Candidate {
    std::size_t tpl;
    Pose pose[2];
    double coarse = 0.0, coarseSecond = 0.0;
};

/// Template `i` at every 6 degrees on its grid, placed on the path's centroid.
Candidate coarseCandidate(std::size_t i, const Grid& grid, const Coords& coarse, Vec2 centre) {
    std::vector<std::pair<double, double>> byTurn;  // cost, turn
    for (double th = 0.0; th < 360.0; th += kCoarseStepDeg)
        byTurn.push_back(
            {meanCost(grid, coarse, {th, centre}, Mapping::IntoFrame, Lookup::Nearest), th});
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
    return c;
}

/// A pattern search from `p` on `cost`: turn and place together, steps halved until the turn's
/// is under 0.2 degrees. cost(q, bound) may stop at +infinity once q's cost is known to reach the
/// bound: only a lower one moves the search.
template <typename Cost>
Pose patternSearch(Pose p, const Cost& cost) {
    double c = cost(p, std::numeric_limits<double>::infinity());
    double stepDeg = 2.0, stepMm = 0.8;
    while (stepDeg > 0.2) {
        bool moved = false;
        const Pose tries[6] = {
            {p.thetaDeg + stepDeg, p.t},         {p.thetaDeg - stepDeg, p.t},
            {p.thetaDeg, p.t + Vec2{stepMm, 0}}, {p.thetaDeg, p.t - Vec2{stepMm, 0}},
            {p.thetaDeg, p.t + Vec2{0, stepMm}}, {p.thetaDeg, p.t - Vec2{0, stepMm}}};
        for (const Pose& q : tries) {
            const double cq = cost(q, c);
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
    return p;
}

/// The path as the search reads it: its points resampled, thinned for the coarse search and
/// halved for the refinement, its centroid and its distance grid.
struct PathView {
    Vec2 centre;
    Coords coarse, search, all;
    Grid grid;
};

/// A fit of one template refined from its coarse candidate: both turns where the second is
/// nearly as good, each by a pattern search on the two-way cost, the better by the full cost.
void refineFit(const PoseTemplate& tpl, const Grid& grid, const Candidate& cand,
               const PathView& path, PoseFit& fit) {
    const Coords tplSearch(halved(tpl.points)), tplAll(tpl.points);
    // The two-way cost, or +infinity once it is known to reach `bound`: twice the bound is
    // reached by the first mean alone, or by the first and the second's mean so far.
    auto cost = [&](const Pose& p, double bound) {
        const double twice = 2.0 * bound;
        const double a =
            meanCost(grid, path.search, p, Mapping::IntoFrame, Lookup::Bilinear, 0.0, twice);
        if (a >= twice) return std::numeric_limits<double>::infinity();
        return 0.5 * (a + meanCost(path.grid, tplSearch, p, Mapping::OntoPath, Lookup::Bilinear, a,
                                   twice));
    };
    auto fullCost = [&](const Pose& p) {
        return 0.5 * (meanCost(grid, path.all, p, Mapping::IntoFrame, Lookup::Bilinear) +
                      meanCost(path.grid, tplAll, p, Mapping::OntoPath, Lookup::Bilinear));
    };
    double fitCost = std::numeric_limits<double>::infinity();
    Pose fitPose;
    for (int k = 0; k < 2; ++k) {
        // The second turn only where the coarse search found it nearly as good.
        if (k == 1 && !(cand.coarseSecond < 1.5 * cand.coarse)) break;
        const Pose p = patternSearch(cand.pose[k], cost);
        if (const double full = fullCost(p); full < fitCost) {
            fitCost = full;
            fitPose = p;
        }
    }
    fit.score_mm = std::sqrt(fitCost);
    fit.position = fitPose.t;
    fit.rotationDeg = tpl.symmetry == 0 ? 0.0 : wrapDeg(fitPose.thetaDeg, 360.0 / tpl.symmetry);
}

}  // namespace

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
    std::vector<Vec2> coarsePoints;
    const std::size_t stride = std::max<std::size_t>(1, points.size() / kCoarsePoints);
    for (std::size_t i = 0; i < points.size(); i += stride) coarsePoints.push_back(points[i]);
    PathView view{lengthCentroid(finite, false), Coords(coarsePoints), Coords(halved(points)),
                  Coords(points), Grid{}};
    view.grid.cell = kPathCell_mm;
    view.grid.portable = portable;
    view.grid.build(finite, false);

    // Coarse: every template at every 6 degrees, placed on the path's centroid; the two best
    // turns at least 15 degrees apart go on to be refined.
    std::vector<Candidate> candidates;
    std::vector<Grid> grids;
    grids.reserve(templates.size());
    for (std::size_t i = 0; i < templates.size(); ++i) {
        grids.push_back(gridOf(templates[i], portable));
        candidates.push_back(coarseCandidate(i, grids.back(), view.coarse, view.centre));
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
        out.fits[i].position = view.centre;
    }
    // Refined: the most promising templates, both turns, turn and place together.
    double bestScore = std::numeric_limits<double>::infinity();
    for (std::size_t r = 0; r < std::min(kRefinedTemplates, order.size()); ++r) {
        const std::size_t i = order[r];
        PoseFit& fit = out.fits[i];
        refineFit(templates[i], grids[i], candidates[i], view, fit);
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
