// How closely a followed path traced its object's contour (ContourFollower.h: measurePath).
#include <algorithm>
#include <vector>

#include "core/control/ContourFollower.h"
#include "core/geometry/ContourReach.h"

namespace activetouch {

namespace {

// The reach of the outlines this thread measured paths on lately. Reach depends on the outline and
// the contact radius alone, and every trial of an object at one pose has the same outline, so a
// sweep over seeds works each out once.
const ContourReach& reachOf(const Polygon& outline, double contactRadius) {
    struct Entry {
        std::vector<Vec2> vertices;
        double radius;
        ContourReach reach;
    };
    thread_local std::vector<Entry> recent;
    for (const Entry& e : recent)
        if (e.radius == contactRadius && e.vertices == outline.vertices()) return e.reach;
    constexpr std::size_t kKept = 16;
    if (recent.size() >= kKept) recent.erase(recent.begin());
    recent.push_back({outline.vertices(), contactRadius, ContourReach(outline, contactRadius)});
    return recent.back().reach;
}

}  // namespace

void measurePath(const Polygon& outline, const std::vector<Vec2>& path, double coverageRadius,
                 double contactRadius, TrialResult& r) {
    r.coverage = 0.0;
    r.meanContourDistance_mm = r.maxContourDistance_mm = 0.0;
    const ContourReach& reach = reachOf(outline, contactRadius);
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
    const std::size_t samples = reach.samples();
    std::size_t inReach = 0, covered = 0;
    for (std::size_t i = 0; i < samples; ++i) {
        if (!reach.reachable(i)) continue;
        ++inReach;
        const Vec2 q = outline.pointAtArcLength(static_cast<double>(i) * outline.perimeter() /
                                                static_cast<double>(samples));
        for (Vec2 p : path)
            if (distance(p, q) <= coverageRadius) {
                ++covered;
                break;
            }
    }
    r.coverage = inReach > 0 ? static_cast<double>(covered) / static_cast<double>(inReach) : 0.0;
}

}  // namespace activetouch
