#include "core/experiment/ReachCautions.h"

#include <algorithm>
#include <cmath>

#include "core/common/NumberText.h"
#include "core/fingertip/FingertipContactModel.h"

namespace activetouch {

namespace {

std::string tenth(double v) {
    return numberText(std::round(v * 10.0) / 10.0);
}

/// "12 %", or "0.2 %" under one per cent, so that a small stretch does not read as none.
std::string percent(double fraction) {
    const double p = fraction * 100.0;
    return numberText(p < 1.0 ? std::round(p * 10.0) / 10.0 : std::round(p)) + " %";
}

/// "a notch, gap or inside corner at (150.2, 121) mm, 3.1 mm across, ...".
std::string describeStretch(const OutOfReach& o, double perimeter) {
    if (o.length_mm >= perimeter - 2.0 * ContourReach::kStep_mm)
        return "the whole outline, which the patch covers at once";
    const bool inward = o.kind == OutOfReach::Kind::Inward;
    return std::string(inward ? "a notch, gap or inside corner"
                              : "a tooth, spike or outside corner") +
           " at (" + tenth(o.middle.x) + ", " + tenth(o.middle.y) + ") mm, " + tenth(o.mouth_mm) +
           " mm across, " + tenth(o.length_mm) + " mm of contour, the patch staying " +
           (o.depthCapped ? "more than " : "") + tenth(o.depth_mm) + " mm off";
}

}  // namespace

double sceneContactRadius(const SceneSpec& scene) {
    // The model a run of this scene builds too (kept for it): its patch is worked out once.
    return FingertipContactModel::shared(scene.fingertip)
        ->edgeContactRadius(scene.tap.contactThreshold, scene.strokeLimitDepth());
}

std::string reachCaution(const Polygon& outline, const ContourReach& reach,
                         const std::string& what) {
    if (reach.stretches().empty()) return {};
    std::vector<OutOfReach> largest = reach.stretches();
    std::stable_sort(largest.begin(), largest.end(), [](const OutOfReach& a, const OutOfReach& b) {
        return a.length_mm > b.length_mm;
    });
    const std::size_t shown = std::min<std::size_t>(3, largest.size());
    std::string list;
    for (std::size_t i = 0; i < shown; ++i)
        list += (i == 0 ? "" : "; ") + describeStretch(largest[i], outline.perimeter());
    if (largest.size() > shown) list += "; and " + std::to_string(largest.size() - shown) + " more";
    const double inReach = reach.reachableFraction();
    return what + ": " + percent(1.0 - inReach) + " of the contour (" +
           tenth((1.0 - inReach) * outline.perimeter()) + " of " + tenth(outline.perimeter()) +
           " mm) has features the fingertip cannot resolve: its contact patch on an edge is " +
           tenth(2.0 * reach.radius_mm()) + " mm across at its narrowest, and " +
           std::to_string(reach.stretches().size()) +
           (reach.stretches().size() == 1 ? " stretch stays" : " stretches stay") + " more than " +
           tenth(reach.tolerance_mm()) + " mm from anywhere it can press. The largest: " + list +
           ". A trial follows across them; its coverage counts only the " + percent(inReach) +
           " within reach. To follow such features, make them wider than the patch (or "
           "enlarge the drawing)";
}

std::vector<std::string> unresolvedFeatureCautions(const ExperimentSpec& e) {
    std::vector<std::string> cautions;
    const double radius = sceneContactRadius(e.scene);
    std::vector<std::vector<Vec2>> seen;
    auto judge = [&](const ObjectSpec& object, const std::string& what) {
        ObjectSpec own = object;  // the object in its own frame: what it is, not where
        own.rotationDeg = 0.0;
        own.offset = {0.0, 0.0};
        const std::vector<Vec2> shape = own.outline().vertices();
        if (std::find(seen.begin(), seen.end(), shape) != seen.end()) return;
        seen.push_back(shape);
        const Polygon outline = object.outline();
        const std::string caution =
            reachCaution(outline, *ContourReach::shared(outline, radius), what);
        if (!caution.empty()) cautions.push_back(caution);
    };
    for (const TrialSpec& t : e.trials) judge(t.object, t.place + " (" + t.label + ")");
    if (e.trials.empty()) judge(e.scene.object, "the scene's object");
    return cautions;
}

}  // namespace activetouch
