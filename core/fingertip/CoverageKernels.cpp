#include "core/fingertip/CoverageKernels.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/common/Avx2Clones.h"

namespace activetouch::coverage {
namespace {

// A point's coverage from its side (1 inside, 0 outside) and its squared distance to the
// outline: whole beyond half a cell, a ramp within it. `full` is exactly 1 or 0, so the ramp is
// frac on the object's side and 1 - frac off it.
inline float fromDistance(double full, double nearest2, double halfCell) {
    const double frac = 0.5 + 0.5 * std::sqrt(nearest2) / halfCell;
    const double ramp = full * frac + (1.0 - full) * (1.0 - frac);
    return static_cast<float>(nearest2 >= halfCell * halfCell ? full : ramp);
}

// Up to kRun points at a time: each edge's crossings and distances for the run, then the run's
// coverage.
constexpr std::size_t kRun = 256;

ACTIVETOUCH_AVX2_CLONES void nearEdgesKernel(const double* ox, const double* oy, std::size_t count,
                                             Vec2 centre, const Edge* edges, std::size_t edgeCount,
                                             bool centreInside, double halfCell, float* out) {
    double flips[kRun], nearest2[kRun];
    for (std::size_t q = 0; q < count; ++q) {
        flips[q] = 0.0;
        nearest2[q] = std::numeric_limits<double>::infinity();
    }
    for (std::size_t k = 0; k < edgeCount; ++k) {
        const Edge& e = edges[k];
        const Vec2 ac = e.a - centre;
        const double acCrossAb = cross(ac, e.ab);
        for (std::size_t q = 0; q < count; ++q) {
            // Crossing of the segment centre -> point with the edge flips the side.
            const Vec2 cp{ox[q], oy[q]};
            const double den = cross(cp, e.ab);
            const double u = acCrossAb / den;      // along centre -> point
            const double v = cross(ac, cp) / den;  // along the edge
            const bool crosses = den != 0.0 && u > 0.0 && u <= 1.0 && v >= 0.0 && v < 1.0;
            flips[q] = crosses ? 1.0 - flips[q] : flips[q];
            const Vec2 ap = (centre + cp) - e.a;
            const double along = dot(ap, e.ab) * e.inverseLength2;
            const double t = along < 0.0 ? 0.0 : (1.0 < along ? 1.0 : along);
            const Vec2 d = ap - t * e.ab;
            const double d2 = dot(d, d);
            nearest2[q] = d2 < nearest2[q] ? d2 : nearest2[q];
        }
    }
    const double inside = centreInside ? 1.0 : 0.0;
    for (std::size_t q = 0; q < count; ++q) {
        const double full = flips[q] == 0.0 ? inside : 1.0 - inside;
        out[q] = fromDistance(full, nearest2[q], halfCell);
    }
}

}  // namespace

void nearEdges(const double* ox, const double* oy, std::size_t count, Vec2 centre,
               const Edge* edges, std::size_t edgeCount, bool centreInside, double halfCell,
               float* out) {
    for (std::size_t from = 0; from < count; from += kRun)
        nearEdgesKernel(ox + from, oy + from, std::min(kRun, count - from), centre, edges,
                        edgeCount, centreInside, halfCell, out + from);
}

}  // namespace activetouch::coverage
