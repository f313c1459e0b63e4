// How closely a followed path traced its object's contour (ContourFollower.h: measurePath).
#include <algorithm>
#include <vector>

#include "core/control/ContourFollower.h"
#include "core/geometry/ContourReach.h"

namespace activetouch {

void measurePath(const Polygon& outline, const std::vector<Vec2>& path, double coverageRadius,
                 double contactRadius, TrialResult& r) {
    r.coverage = 0.0;
    r.meanContourDistance_mm = r.maxContourDistance_mm = 0.0;
    const auto kept = ContourReach::shared(outline, contactRadius);
    const ContourReach& reach = *kept;
    r.reachable = reach.reachableFraction();
    if (path.empty()) return;
    double sum = 0.0;
    for (Vec2 p : path) {
        const double d = outline.nearestOutlinePoint(p).distance;
        sum += d;
        r.maxContourDistance_mm = std::max(r.maxContourDistance_mm, d);
    }
    r.meanContourDistance_mm = sum / static_cast<double>(path.size());
    // Coverage: contour points within reach, every half millimetre, with a tap within the radius.
    // Neighbouring samples are covered by neighbouring taps: each search starts at the tap that
    // covered the last one and goes round the path once (only whether one does counts).
    const std::size_t samples = reach.samples(), taps = path.size();
    std::size_t inReach = 0, covered = 0, lastHit = 0;
    for (std::size_t i = 0; i < samples; ++i) {
        if (!reach.reachable(i)) continue;
        ++inReach;
        const Vec2 q = outline.pointAtArcLength(static_cast<double>(i) * outline.perimeter() /
                                                static_cast<double>(samples));
        for (std::size_t k = 0, j = lastHit; k < taps; ++k, j = j + 1 == taps ? 0 : j + 1)
            if (distance(path[j], q) <= coverageRadius) {
                ++covered;
                lastHit = j;
                break;
            }
    }
    r.coverage = inReach > 0 ? static_cast<double>(covered) / static_cast<double>(inReach) : 0.0;
}

}  // namespace activetouch
