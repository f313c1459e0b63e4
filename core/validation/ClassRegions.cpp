#include "core/validation/ClassRegions.h"

#include <algorithm>

namespace activetouch {

std::vector<Region> computeClassRegions(const FingertipContactModel& model, const ClassSet& classes,
                                        const TapSpec& tap, double strokeLimitDepth) {
    std::vector<Region> regions(static_cast<std::size_t>(classes.classCount()), Region::Edge);
    std::vector<double> pressures(static_cast<std::size_t>(model.taxelCount()));
    for (std::size_t o = 0; o < classes.orientationsDeg.size(); ++o) {
        // A half-plane object far larger than the fingertip, its edge through the origin.
        const Vec2 n = directionFromDegrees(classes.orientationsDeg[o]);
        const Vec2 t{-n.y, n.x};
        const double big = 1000.0;
        const Polygon halfPlane({big * t, -big * t, -big * t - big * n, big * t - big * n});
        for (int p = 1; p <= classes.positions; ++p) {
            auto contact = model.contactAt(halfPlane, classes.offsetOf(p) * n);
            const double depth = contact.depthReaching(tap.contactThreshold, strokeLimitDepth)
                                     .value_or(strokeLimitDepth);
            contact.taxelPressures(depth, pressures.data());
            const double peak = *std::max_element(pressures.begin(), pressures.end());
            Region r = Region::Edge;
            if (peak < tap.noiseFloor)
                r = Region::Air;
            else if (contact.patchFullyOnObject(depth))
                r = Region::Plane;
            regions[static_cast<std::size_t>(classes.classOf(static_cast<int>(o), p))] = r;
        }
    }
    return regions;
}

}  // namespace activetouch
