#include "core/validation/TrainingProtocol.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/common/NumberText.h"

namespace activetouch {

bool TrainingProtocolSettings::isTrainingSet(int set) const {
    return std::find(trainingSets.begin(), trainingSets.end(), set) != trainingSets.end();
}

std::string TrainingProtocolSettings::problem() const {
    if (dataSets < 2) return "at least 2 data sets are needed (one to train, one to test)";
    if (trainingSets.empty()) return "name at least one training set";
    for (int s : trainingSets)
        if (s < 1 || s > dataSets)
            return "training set " + std::to_string(s) + " does not exist (sets are 1.." +
                   std::to_string(dataSets) + ")";
    if (static_cast<int>(trainingSets.size()) >= dataSets)
        return "every set trains; leave at least one set to test";
    if (tapsPerClass < 1) return "taps per class must be at least 1";
    if (!(placementJitter_mm >= 0.0)) return "placement jitter must not be negative";
    if (!std::isfinite(testOffset_mm) || std::abs(testOffset_mm) > 5.0)
        return "test offset must be within +-5 mm";
    return {};
}

std::vector<EdgeSite> edgeSites(const Polygon& object, const ClassSet& classes) {
    std::vector<EdgeSite> sites;
    for (double deg : classes.orientationsDeg) {
        const Vec2 want = directionFromDegrees(deg);
        double bestLength = 0.0;
        EdgeSite best{};
        for (std::size_t e = 0; e < object.size(); ++e) {
            const Vec2 n = object.outwardNormal(e);
            const double len = distance(object.vertex(e), object.vertex(e + 1));
            if (dot(n, want) > 1.0 - 1e-6 && len > bestLength) {
                bestLength = len;
                best = {0.5 * (object.vertex(e) + object.vertex(e + 1)), n};
            }
        }
        if (bestLength == 0.0)
            throw std::invalid_argument(
                "the training object has no edge facing " + ClassSet::orientationName(deg) + " (" +
                numberText(deg) + " deg); train on a shape with an edge for every orientation");
        sites.push_back(best);
    }
    return sites;
}

std::string trainingPosesProblem(const Polygon& object, const ClassSet& classes,
                                 const TrainingProtocolSettings& settings, Vec2 travel_mm) {
    std::vector<EdgeSite> sites;
    try {
        sites = edgeSites(object, classes);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    const double margin = 4.0 * settings.placementJitter_mm;
    for (std::size_t o = 0; o < sites.size(); ++o) {
        const std::string edge = ClassSet::orientationName(classes.orientationsDeg[o]) + " edge";
        for (int p = 1; p <= classes.positions; ++p) {
            for (const double shift : {0.0, settings.testOffset_mm}) {
                const double offset = classes.offsetOf(p) + shift;
                const Vec2 pose = sites[o].poseAt(offset);
                if (offset < 0.0 && !object.contains(pose))
                    return "position " + std::to_string(p) + " at the " + edge + " puts the tip " +
                           numberText(-offset) +
                           " mm inside the edge, past the far side of the training object; use "
                           "fewer positions, a smaller position_step_mm or a larger object";
                if (pose.x - margin < 0.0 || pose.y - margin < 0.0 ||
                    pose.x + margin > travel_mm.x || pose.y + margin > travel_mm.y)
                    return "position " + std::to_string(p) + " at the " + edge + " taps at (" +
                           numberText(pose.x) + ", " + numberText(pose.y) + ") mm" +
                           (margin > 0.0 ? " (+-" + numberText(margin) + " mm placement jitter)"
                                         : std::string()) +
                           ", outside the stage travel (0.." + numberText(travel_mm.x) + ", 0.." +
                           numberText(travel_mm.y) +
                           " mm); move the training object away from the travel's end";
            }
        }
    }
    return {};
}

std::vector<CollectedTap> collectTrainingTaps(
    Rig& rig, const Polygon& object, const ClassSet& classes,
    const TrainingProtocolSettings& settings, RandomStream rng,
    const std::function<bool(const CollectedTap&)>& onTap) {
    const auto sites = edgeSites(object, classes);
    std::vector<CollectedTap> taps;
    taps.reserve(
        static_cast<std::size_t>(settings.dataSets * classes.classCount() * settings.tapsPerClass));
    for (int set = 1; set <= settings.dataSets; ++set) {
        // Re-placing the object moves it relative to the commanded poses.
        const Vec2 placement{rng.normal(0, settings.placementJitter_mm),
                             rng.normal(0, settings.placementJitter_mm)};
        const double shift = settings.isTrainingSet(set) ? 0.0 : settings.testOffset_mm;
        for (std::size_t o = 0; o < sites.size(); ++o) {
            for (int p = 1; p <= classes.positions; ++p) {
                for (int r = 0; r < settings.tapsPerClass; ++r) {
                    const double offset = classes.offsetOf(p) + shift;
                    const Vec2 pose = sites[o].poseAt(offset) + placement;
                    CollectedTap c;
                    c.record = rig.tapAt(pose);
                    c.dataSet = set;
                    c.cls = classes.classOf(static_cast<int>(o), p);
                    c.trueOffset_mm = sites[o].offsetOf(pose);
                    taps.push_back(std::move(c));
                    if (onTap && !onTap(taps.back())) return taps;
                }
            }
        }
    }
    return taps;
}

}  // namespace activetouch
