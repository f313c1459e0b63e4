#include "core/fingertip/FingertipContactModel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/common/Avx2Clones.h"
#include "core/common/RecentlyKept.h"
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
        offsetX_.push_back(grid[q].offset.x);
        offsetY_.push_back(grid[q].offset.y);
        patchRadius_ = std::max(patchRadius_, norm(grid[q].offset));
    }
}

std::shared_ptr<const FingertipContactModel> FingertipContactModel::shared(
    const FingertipSpec& spec) {
    // Every field of the spec (the name is kept beside), exactly.
    std::vector<double> key{spec.radius,       spec.capStart,        spec.tipEnd,
                            spec.mountTiltDeg, spec.mountHeadingDeg, spec.receptiveFieldSigma,
                            spec.countsPerMm,  spec.gridStep,        spec.maxIndentation};
    for (const TaxelPosition& t : spec.taxels) key.insert(key.end(), {t.x, t.y, t.z});
    static RecentlyKept<std::pair<std::string, std::vector<double>>, FingertipContactModel, 4> kept;
    return kept.get({spec.name, std::move(key)},
                    [&] { return std::make_shared<const FingertipContactModel>(spec); });
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
    // Only the points covered so far are ever read: no need to clear the buffers.
    coverage_.reset(new float[model.points_.size()]);
    touched_.reset(new std::uint32_t[model.points_.size()]);
}

namespace {

// Coverage of `count` patch points (offsets ox, oy from the centre) by an object bounded near the
// patch by one straight line (unit normal n, the centre `centreSide` from it): 1 or 0 by side
// beyond half a cell, a linear ramp within it. Written without branches, so that it runs several
// points to an instruction; cloned for AVX2, each clone giving the same values (no FMA).
ACTIVETOUCH_AVX2_CLONES void coverAcrossLine(const double* ox, const double* oy, std::size_t count,
                                             Vec2 n, double centreSide, bool centreInside,
                                             double halfCell, float* out) {
    const double towardCentre = centreSide > 0.0 ? 1.0 : -1.0;
    const double inFull = centreInside ? 1.0 : 0.0;  // a point on the centre's side
    const double outFull = 1.0 - inFull;
    // (A point exactly on the line gets 0.5 whichever side it is counted on.)
    for (std::size_t q = 0; q < count; ++q) {
        const double side = centreSide + (ox[q] * n.x + oy[q] * n.y);
        const double full = side * towardCentre > 0.0 ? inFull : outFull;
        const double d = std::abs(side);
        const double frac = 0.5 + 0.5 * d / halfCell;
        // full is exactly 1 or 0: the ramp is frac on the object's side, 1 - frac off it.
        const double ramp = full * frac + (1.0 - full) * (1.0 - frac);
        out[q] = static_cast<float>(d >= halfCell ? full : ramp);
    }
}

}  // namespace

void FingertipContactModel::Contact::coverUpTo(double height) {
    const auto& pts = model_->points_;
    std::size_t end = covered_;
    while (end < pts.size() && pts[end].height < height) ++end;
    if (end > covered_) coverRange(end);
}

void FingertipContactModel::Contact::coverRange(std::size_t end) {
    const std::size_t from = covered_;
    float* c = coverage_.get();
    if (nearEdges_.empty()) {
        std::fill(c + from, c + end, centreInside_ ? 1.0f : 0.0f);
    } else if (singleLine_) {
        // One straight edge crosses the patch: a point's side and distance are one dot product.
        coverAcrossLine(model_->offsetX_.data() + from, model_->offsetY_.data() + from, end - from,
                        lineNormal_, centreSide_, centreInside_, 0.5 * model_->spec_.gridStep,
                        c + from);
    } else {
        coverage::nearEdges(model_->offsetX_.data() + from, model_->offsetY_.data() + from,
                            end - from, centre_, nearEdges_.data(), nearEdges_.size(),
                            centreInside_, 0.5 * model_->spec_.gridStep, c + from);
    }
    std::uint32_t* listed = touched_.get();
    std::size_t n = touchedCount_;
    for (std::size_t q = from; q < end; ++q) {  // each point written, kept where it counts
        listed[n] = static_cast<std::uint32_t>(q);
        n += c[q] != 0.0f ? 1 : 0;
    }
    touchedCount_ = n;
    covered_ = end;
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
    // breakpoints with running sums S0 = sum c W and S1 = sum c W h. Points off the object add
    // nothing: only those on it are walked, covered a run at a time as the walk needs them.
    constexpr std::size_t kRun = 64;
    const auto& pts = model_->points_;
    double s0 = 0.0, s1 = 0.0;
    for (std::size_t i = 0;; ++i) {
        while (i == touchedCount_ && covered_ < pts.size() && pts[covered_].height < maxDepth) {
            std::size_t end = covered_;
            while (end < pts.size() && end < covered_ + kRun && pts[end].height < maxDepth) ++end;
            coverRange(end);
        }
        if (i == touchedCount_) break;
        const std::size_t q = touched_[i];
        const double h = pts[q].height;
        if (h >= maxDepth) break;
        if (s0 > 0.0 && h * s0 - s1 >= threshold) return (threshold + s1) / s0;
        const double cw = coverage_[q] * pts[q].weightSum;
        s0 += cw;
        s1 += cw * h;
    }
    if (s0 > 0.0 && maxDepth * s0 - s1 >= threshold) return (threshold + s1) / s0;
    return std::nullopt;
}

namespace {

using Float8 = float __attribute__((vector_size(32)));

// Running sums over the listed patch points (those on the object) in height order: A += c w and
// B += c w h, sixteen taxel lanes (zero-padded) per point. Cloned for AVX2; each lane sees the
// same operations in either clone.
ACTIVETOUCH_AVX2_CLONES void sweepPatch(const float* weights, const float* coverage,
                                        const float* heights, const std::uint32_t* listed,
                                        std::size_t from, std::size_t to, float* sumA,
                                        float* sumB) {
    // Two halves of eight lanes each, so that the sums stay in registers.
    Float8 a0, a1, b0, b1;
    std::memcpy(&a0, sumA, sizeof a0);
    std::memcpy(&a1, sumA + 8, sizeof a1);
    std::memcpy(&b0, sumB, sizeof b0);
    std::memcpy(&b1, sumB + 8, sizeof b1);
    for (std::size_t i = from; i < to; ++i) {
        const std::size_t q = listed[i];
        Float8 r0, r1;
        std::memcpy(&r0, weights + q * 16, sizeof r0);
        std::memcpy(&r1, weights + q * 16 + 8, sizeof r1);
        const float c = coverage[q], h = heights[q];
        const Float8 cw0 = c * r0, cw1 = c * r1;
        a0 += cw0;
        a1 += cw1;
        b0 += h * cw0;
        b1 += h * cw1;
    }
    std::memcpy(sumA, &a0, sizeof a0);
    std::memcpy(sumA + 8, &a1, sizeof a1);
    std::memcpy(sumB, &b0, sizeof b0);
    std::memcpy(sumB + 8, &b1, sizeof b1);
}

}  // namespace

void FingertipContactModel::Contact::taxelPressuresAtDepths(const double* depths, std::size_t count,
                                                            double* out) {
    static_assert(kLanes == 16, "sweepPatch works on sixteen lanes");
    const int K = model_->taxelCount_;
    const auto& pts = model_->points_;
    alignas(64) float sumA[kLanes] = {}, sumB[kLanes] = {};
    std::size_t i = 0;  // into touched_: the points on the object summed so far
    for (std::size_t d = 0; d < count; ++d) {
        const double depth = depths[d];
        double* o = out + d * static_cast<std::size_t>(K);
        if (depth <= 0.0) {
            std::fill(o, o + K, 0.0);
            continue;
        }
        coverUpTo(depth);
        std::size_t end = i;
        while (end < touchedCount_ && pts[touched_[end]].height < depth) ++end;
        sweepPatch(model_->weights_.data(), coverage_.get(), model_->heights_.data(),
                   touched_.get(), i, end, sumA, sumB);
        i = end;
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
