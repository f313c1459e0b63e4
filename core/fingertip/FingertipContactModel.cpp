#include "core/fingertip/FingertipContactModel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/common/Avx2Clones.h"
#include "core/common/VectorState.h"

namespace activetouch {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The body is built with the finger pointing along +Y of its own frame, tilted down by the
// mount angle, pad facing down. Finger axes in that frame (x_f: toward the tip, y_f: toward the
// pad, z_f: lateral): x_f = (0, c, -s), y_f = (0, -s, -c), z_f = (-1, 0, 0).
struct Tilt {
    double c, s;
    explicit Tilt(double degrees)
        : c(std::cos(degrees * M_PI / 180)), s(std::sin(degrees * M_PI / 180)) {}
    double worldX(double, double, double zf) const { return -zf; }
    double worldY(double xf, double yf) const { return c * xf - s * yf; }
    double worldZ(double xf, double yf) const { return -s * xf - c * yf; }
};

}  // namespace

double FingertipContactModel::lowestBodyHeight(double X, double Y) const {
    // Where a vertical line through (X, Y) first enters the body (smallest world z), or +inf.
    const Tilt tilt(spec_.mountTiltDeg);
    const double R = spec_.radius, x0 = spec_.capStart, L = spec_.tipEnd - spec_.capStart;
    // Along the line P(t) = (X, Y, t): x_f = cY - s t, y_f = -sY - c t, z_f = -X.
    const double zf = -X;
    double best = kInf;
    auto consider = [&](double t, bool onCap) {
        const double xf = tilt.c * Y - tilt.s * t;
        if (onCap ? xf >= x0 : xf <= x0) best = std::min(best, t);
    };
    // Cylinder y_f^2 + z_f^2 = R^2.
    const double rr = R * R - zf * zf;
    if (rr >= 0) {
        const double root = std::sqrt(rr);
        for (double yf : {root, -root}) consider((-tilt.s * Y - yf) / tilt.c, false);
    }
    // Cap ((x_f - x0)/L)^2 + (y_f^2 + z_f^2)/R^2 = 1, a quadratic in t.
    const double ax = -tilt.s / L, bx = (tilt.c * Y - x0) / L;  // (x_f - x0)/L = ax t + bx
    const double ay = -tilt.c / R, by = -tilt.s * Y / R;        // y_f / R = ay t + by
    const double qa = ax * ax + ay * ay;
    const double qb = 2 * (ax * bx + ay * by);
    const double qc = bx * bx + by * by + (zf * zf) / (R * R) - 1.0;
    const double disc = qb * qb - 4 * qa * qc;
    if (disc >= 0) {
        const double sq = std::sqrt(disc);
        consider((-qb - sq) / (2 * qa), true);
        consider((-qb + sq) / (2 * qa), true);
    }
    return best;
}

FingertipContactModel::FingertipContactModel(const FingertipSpec& spec) : spec_(spec) {
    clearUpperVectorState();  // the tables below take thousands of exp calls
    if (spec.taxels.empty()) throw std::invalid_argument("the fingertip has no taxels");
    if (spec.taxels.size() > static_cast<std::size_t>(kLanes))
        throw std::invalid_argument("the contact model handles at most " + std::to_string(kLanes) +
                                    " taxels per fingertip");
    if (!(spec.mountTiltDeg > 1 && spec.mountTiltDeg < 89))
        throw std::invalid_argument("mount tilt must be between 1 and 89 degrees");
    if (!(spec.radius > 0) || !(spec.tipEnd > spec.capStart))
        throw std::invalid_argument("the body needs a positive radius and tip_end > cap_start");
    if (!(spec.gridStep > 0.05 && spec.gridStep <= 2.0))
        throw std::invalid_argument("grid step must be in (0.05, 2] mm");
    if (!(spec.receptiveFieldSigma > 0) || !(spec.countsPerMm > 0) || !(spec.maxIndentation > 0))
        throw std::invalid_argument("receptive field, gain and max indentation must be positive");

    taxelCount_ = static_cast<int>(spec.taxels.size());
    const Tilt tilt(spec.mountTiltDeg);
    const double R = spec.radius, x0 = spec.capStart, L = spec.tipEnd - spec.capStart;

    // First-contact point: the cap point whose outward normal points straight down; in the
    // finger frame that normal is (s, c, 0), so the point is x0 + lambda s L^2, lambda c R^2.
    const double lambda = 1.0 / std::hypot(tilt.s * L, tilt.c * R);
    const double xl = x0 + lambda * tilt.s * L * L, yl = lambda * tilt.c * R * R;
    lowestY_ = tilt.worldY(xl, yl);
    lowestZ_ = tilt.worldZ(xl, yl);
    firstContactForward_ = lowestY_;
    firstContactDrop_ = -lowestZ_;
    buildPatch(placeTaxels());
}

double FingertipContactModel::placeTaxels() {
    const FingertipSpec& spec = spec_;
    const Tilt tilt(spec.mountTiltDeg);
    const double R = spec.radius, x0 = spec.capStart, L = spec.tipEnd - spec.capStart;
    const double headingTurn = spec.mountHeadingDeg - 90.0;
    auto toPlane = [&](double X, double Y) { return rotated(Vec2{X, Y - lowestY_}, headingTurn); };
    // Taxels sit on the body surface at their published axial position and angle around the axis.
    double reach = 0.0;
    for (const auto& t : spec.taxels) {
        const double xf = std::clamp(t.x, -1e9, spec.tipEnd);
        double r = R;
        if (xf > x0) r = R * std::sqrt(std::max(0.0, 1.0 - std::pow((xf - x0) / L, 2)));
        const double phi = std::atan2(t.z, t.y);
        const double yf = r * std::cos(phi), zf = r * std::sin(phi);
        const Vec2 p = toPlane(tilt.worldX(xf, yf, zf), tilt.worldY(xf, yf));
        projectedTaxels_.push_back(p);
        taxelHeights_.push_back(tilt.worldZ(xf, yf) - lowestZ_);
        reach = std::max(reach, norm(p));
    }
    return reach;
}

void FingertipContactModel::buildPatch(double reach) {
    const FingertipSpec& spec = spec_;
    const double R = spec.radius, L = spec.tipEnd - spec.capStart;
    const double headingTurn = spec.mountHeadingDeg - 90.0;
    // Patch points: a square grid around the first-contact point, kept where the body comes
    // within maxIndentation of the plane.
    const double step = spec.gridStep;
    const double sigma = spec.receptiveFieldSigma;
    const double half = std::max(reach + 3.5 * sigma, 2.0 * (R + L));
    const int n = static_cast<int>(std::ceil(half / step));
    struct Candidate {
        Vec2 offset;
        double height;
    };
    std::vector<Candidate> grid;
    grid.reserve(static_cast<std::size_t>((2 * n + 1) * (2 * n + 1)));
    for (int i = -n; i <= n; ++i) {
        for (int j = -n; j <= n; ++j) {
            const Vec2 offset{i * step, j * step};
            const Vec2 body = rotated(offset, -headingTurn);
            const double h = lowestBodyHeight(body.x, body.y + lowestY_) - lowestZ_;
            grid.push_back({offset, h});
        }
    }
    // Receptive fields: Gaussian over the plane, normalised over the whole grid so that a taxel
    // whose field partly never meets the plane reads proportionally less.
    std::vector<double> norms(static_cast<std::size_t>(taxelCount_), 0.0);
    auto gauss = [&](Vec2 a, Vec2 b) {
        const Vec2 d = a - b;
        return std::exp(-dot(d, d) / (2 * sigma * sigma));
    };
    for (const auto& c : grid)
        for (int k = 0; k < taxelCount_; ++k)
            norms[static_cast<std::size_t>(k)] +=
                gauss(c.offset, projectedTaxels_[static_cast<std::size_t>(k)]);

    std::vector<std::size_t> kept;
    for (std::size_t q = 0; q < grid.size(); ++q)
        if (grid[q].height <= spec.maxIndentation) kept.push_back(q);
    std::stable_sort(kept.begin(), kept.end(),
                     [&](std::size_t a, std::size_t b) { return grid[a].height < grid[b].height; });
    points_.reserve(kept.size());
    weights_.assign(kept.size() * kLanes, 0.0f);
    for (std::size_t q : kept) {
        float sum = 0.0f;
        float* row = weights_.data() + points_.size() * kLanes;
        for (int k = 0; k < taxelCount_; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            double w = gauss(grid[q].offset, projectedTaxels_[kk]) / norms[kk];
            if (w < 1e-6) w = 0.0;
            row[k] = static_cast<float>(w * spec.countsPerMm);
            sum += row[k];
        }
        points_.push_back({grid[q].offset, grid[q].height, sum});
        heights_.push_back(static_cast<float>(grid[q].height));
        patchRadius_ = std::max(patchRadius_, norm(grid[q].offset));
    }
}

double FingertipContactModel::surfaceHeightAt(Vec2 offset) const {
    const Vec2 body = rotated(offset, -(spec_.mountHeadingDeg - 90.0));
    return lowestBodyHeight(body.x, body.y + lowestY_) - lowestZ_;
}

double FingertipContactModel::footprintHalfWidth(double depth) const {
    const auto pressed = static_cast<std::size_t>(
        std::upper_bound(heights_.begin(), heights_.end(), static_cast<float>(depth)) -
        heights_.begin());
    if (pressed == 0) return 0.0;
    double narrowest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 180; k += 5) {  // the footprint's extent along each direction
        const Vec2 d = directionFromDegrees(k);
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (std::size_t q = 0; q < pressed; ++q) {
            const double t = dot(points_[q].offset, d);
            lo = std::min(lo, t);
            hi = std::max(hi, t);
        }
        narrowest = std::min(narrowest, hi - lo);
    }
    // Each patch point stands for a cell a grid step across.
    return 0.5 * (narrowest + spec_.gridStep);
}

double FingertipContactModel::edgeContactRadius(double threshold, double maxDepth) const {
    // A square far larger than the patch, the tip centred on its lower edge.
    const double side = 4.0 * (patchRadius_ + spec_.gridStep);
    const Polygon object({{-side, 0.0}, {side, 0.0}, {side, 2.0 * side}, {-side, 2.0 * side}});
    auto contact = contactAt(object, {0.0, 0.0});
    return footprintHalfWidth(contact.depthReaching(threshold, maxDepth).value_or(maxDepth));
}

FingertipContactModel::Contact FingertipContactModel::contactAt(const Polygon& object,
                                                                Vec2 centre) const {
    return Contact(*this, object, centre);
}

FingertipContactModel::Contact::Contact(const FingertipContactModel& model, const Polygon& object,
                                        Vec2 centre)
    : model_(&model), centre_(centre) {
    centreInside_ = object.contains(centre);
    // An edge matters only if it passes within the patch radius (plus half a cell for the
    // coverage ramp); every other point's side is the centre's.
    const double reach = model.patchRadius_ + model.spec_.gridStep;
    for (std::size_t e = 0; e < object.size(); ++e) {
        const Vec2 a = object.vertex(e), b = object.vertex(e + 1), ab = b - a;
        const double inv = 1.0 / dot(ab, ab);
        const double t = std::clamp(dot(centre - a, ab) * inv, 0.0, 1.0);
        if (distance(centre, a + t * ab) <= reach) nearEdges_.push_back({a, ab, inv});
    }
    if (nearEdges_.size() == 1) {
        const NearEdge& e = nearEdges_.front();
        const double length = std::sqrt(1.0 / e.inverseLength2);
        const double along = dot(centre - e.a, e.ab) / length;
        if (along - reach > 0.0 && along + reach < length) {
            singleLine_ = true;
            lineNormal_ = (1.0 / length) * Vec2{e.ab.y, -e.ab.x};
            centreSide_ = dot(centre - e.a, lineNormal_);
        }
    }
    coverage_.resize(model.points_.size(), 0.0f);
}

float FingertipContactModel::Contact::coverageOf(std::size_t q) const {
    if (nearEdges_.empty()) return centreInside_ ? 1.0f : 0.0f;
    const double halfCell = 0.5 * model_->spec_.gridStep;
    if (singleLine_) {
        const double side = centreSide_ + dot(model_->points_[q].offset, lineNormal_);
        const bool inside = (side > 0.0) == (centreSide_ > 0.0) ? centreInside_ : !centreInside_;
        const double d = std::abs(side);
        if (d >= halfCell) return inside ? 1.0f : 0.0f;
        const double frac = 0.5 + 0.5 * d / halfCell;
        return static_cast<float>(inside ? frac : 1.0 - frac);
    }
    const Vec2 cp = model_->points_[q].offset;  // from the centre to the point
    const Vec2 p = centre_ + cp;
    bool inside = centreInside_;
    double nearest2 = kInf;
    for (const NearEdge& e : nearEdges_) {
        // Crossing of the segment centre -> p with the edge flips the side.
        const double den = cross(cp, e.ab);
        if (den != 0.0) {
            const Vec2 ac = e.a - centre_;
            const double u = cross(ac, e.ab) / den;  // along centre -> p
            const double v = cross(ac, cp) / den;    // along the edge
            if (u > 0.0 && u <= 1.0 && v >= 0.0 && v < 1.0) inside = !inside;
        }
        const Vec2 ap = p - e.a;
        const double t = std::clamp(dot(ap, e.ab) * e.inverseLength2, 0.0, 1.0);
        const Vec2 d = ap - t * e.ab;
        nearest2 = std::min(nearest2, dot(d, d));
    }
    // Area-weighted coverage of the grid cell: a linear ramp across the outline, so that taps
    // vary continuously with pose instead of jumping by whole cells.
    if (nearest2 >= halfCell * halfCell) return inside ? 1.0f : 0.0f;
    const double frac = 0.5 + 0.5 * std::sqrt(nearest2) / halfCell;
    return static_cast<float>(inside ? frac : 1.0 - frac);
}

void FingertipContactModel::Contact::coverUpTo(double height) {
    const auto& pts = model_->points_;
    while (covered_ < pts.size() && pts[covered_].height < height) {
        coverage_[covered_] = coverageOf(covered_);
        ++covered_;
    }
}

double FingertipContactModel::Contact::totalPressure(double depth) {
    coverUpTo(depth);
    const auto& pts = model_->points_;
    double total = 0.0;
    for (std::size_t q = 0; q < pts.size() && pts[q].height < depth; ++q)
        total += coverage_[q] * pts[q].weightSum * (depth - pts[q].height);
    return total;
}

std::optional<double> FingertipContactModel::Contact::depthReaching(double threshold,
                                                                    double maxDepth) {
    // F(d) = sum_q c_q W_q (d - h_q) over h_q < d is piecewise linear and increasing: walk the
    // breakpoints with running sums S0 = sum c W and S1 = sum c W h.
    const auto& pts = model_->points_;
    double s0 = 0.0, s1 = 0.0;
    for (std::size_t q = 0; q < pts.size(); ++q) {
        const double h = pts[q].height;
        if (h >= maxDepth) break;
        if (s0 > 0.0 && h * s0 - s1 >= threshold) return (threshold + s1) / s0;
        if (q >= covered_) {
            coverage_[q] = coverageOf(q);
            covered_ = q + 1;
        }
        const double cw = coverage_[q] * pts[q].weightSum;
        s0 += cw;
        s1 += cw * h;
    }
    if (s0 > 0.0 && maxDepth * s0 - s1 >= threshold) return (threshold + s1) / s0;
    return std::nullopt;
}

namespace {

using Float16 = float __attribute__((vector_size(64)));

// Running sums over patch points in height order: A += c w and B += c w h, sixteen taxel lanes
// (zero-padded) per point. Cloned for AVX2; each lane sees the same operations in either clone.
ACTIVETOUCH_AVX2_CLONES void sweepPatch(const float* weights, const float* coverage,
                                        const float* heights, std::size_t from, std::size_t to,
                                        float* sumA, float* sumB) {
    Float16 a, b;
    std::memcpy(&a, sumA, sizeof a);
    std::memcpy(&b, sumB, sizeof b);
    for (std::size_t q = from; q < to; ++q) {
        Float16 row;
        std::memcpy(&row, weights + q * 16, sizeof row);
        const Float16 cw = coverage[q] * row;
        a += cw;
        b += heights[q] * cw;
    }
    std::memcpy(sumA, &a, sizeof a);
    std::memcpy(sumB, &b, sizeof b);
}

}  // namespace

void FingertipContactModel::Contact::taxelPressuresAtDepths(const double* depths, std::size_t count,
                                                            double* out) {
    static_assert(kLanes == 16, "sweepPatch works on sixteen lanes");
    const int K = model_->taxelCount_;
    const auto& pts = model_->points_;
    alignas(64) float sumA[kLanes] = {}, sumB[kLanes] = {};
    std::size_t q = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const double depth = depths[i];
        double* o = out + i * static_cast<std::size_t>(K);
        if (depth <= 0.0) {
            std::fill(o, o + K, 0.0);
            continue;
        }
        coverUpTo(depth);
        std::size_t end = q;
        while (end < pts.size() && pts[end].height < depth) ++end;
        sweepPatch(model_->weights_.data(), coverage_.data(), model_->heights_.data(), q, end, sumA,
                   sumB);
        q = end;
        for (int k = 0; k < K; ++k)
            o[k] = std::max(0.0, depth * sumA[k] - static_cast<double>(sumB[k]));
    }
}

bool FingertipContactModel::Contact::patchFullyOnObject(double depth) {
    coverUpTo(depth);
    const auto& pts = model_->points_;
    for (std::size_t q = 0; q < pts.size() && pts[q].height < depth; ++q)
        if (coverage_[q] < 1.0f) return false;
    return true;
}

}  // namespace activetouch
