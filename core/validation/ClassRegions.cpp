#include "core/validation/ClassRegions.h"

#include <algorithm>
#include <cmath>

namespace activetouch {
namespace {
constexpr double kNoPressure = 1e-9;  ///< counts: an ideal tap this light touches nothing
}  // namespace

std::vector<IdealClassContact> idealClassContacts(const FingertipContactModel& model,
                                                  const ClassSet& classes, const TapSpec& tap,
                                                  double strokeLimitDepth) {
    std::vector<IdealClassContact> contacts(static_cast<std::size_t>(classes.classCount()));
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
            contacts[static_cast<std::size_t>(classes.classOf(static_cast<int>(o), p))] = {
                *std::max_element(pressures.begin(), pressures.end()),
                contact.patchFullyOnObject(depth)};
        }
    }
    return contacts;
}

std::vector<Region> classRegions(const std::vector<IdealClassContact>& contacts,
                                 double noiseFloor) {
    std::vector<Region> regions;
    regions.reserve(contacts.size());
    for (const auto& c : contacts)
        regions.push_back(c.peak < noiseFloor ? Region::Air
                          : c.fullyOnObject   ? Region::Plane
                                              : Region::Edge);
    return regions;
}

std::vector<Region> computeClassRegions(const FingertipContactModel& model, const ClassSet& classes,
                                        const TapSpec& tap, double strokeLimitDepth) {
    return classRegions(idealClassContacts(model, classes, tap, strokeLimitDepth), tap.noiseFloor);
}

std::optional<MeasuredNoiseFloor> measureNoiseFloor(const std::vector<IdealClassContact>& contacts,
                                                    const std::vector<ClassTap>& taps) {
    std::vector<double> peaks;
    for (const ClassTap& t : taps) {
        if (t.cls < 0 || t.cls >= static_cast<int>(contacts.size()) || !t.tap ||
            t.tap->samples.empty() || contacts[static_cast<std::size_t>(t.cls)].peak > kNoPressure)
            continue;
        const double peak = *std::max_element(t.tap->samples.begin(), t.tap->samples.end());
        if (std::isfinite(peak)) peaks.push_back(peak);
    }
    if (peaks.empty()) return std::nullopt;
    std::sort(peaks.begin(), peaks.end());
    const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(peaks.size())));
    return MeasuredNoiseFloor{peaks[std::max<std::size_t>(rank, 1) - 1],
                              static_cast<int>(peaks.size())};
}

}  // namespace activetouch
