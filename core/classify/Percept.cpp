#include "core/classify/Percept.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/classify/ContinuousEdge.h"

namespace activetouch {

std::string Percept::shapeClass() const {
    if (region == Region::Plane) return "plane";
    if (region == Region::Air) return "air";
    return ClassSet::orientationName(orientationDeg) + " edge";
}

Percept perceptOf(int cls, double posterior, const ClassSet& classes) {
    Percept p;
    p.cls = cls;
    p.posterior = posterior;
    p.region = classes.regionOf(cls);
    p.orientationDeg = classes.orientationDegOf(cls);
    p.position = classes.positionOf(cls);
    p.offset_mm = classes.offsetOf(p.position);
    return p;
}

Percept perceive(const HistogramClassifier& classifier, const ClassSet& classes, const Tap& tap) {
    const auto d = classifier.decide(tap);
    return perceptOf(d.cls, d.posterior, classes);
}

Percept perceiveContinuous(const ClassSet& classes, const double* ll, double temperature) {
    const int n = classes.classCount();
    const int best = argmaxLowestIndex(ll, n);
    const double top = ll[best];
    Percept p =
        perceptOf(best, std::isfinite(top) ? std::exp(top - logSumExp(ll, n)) : 0.0, classes);
    p.continuous = true;
    if (p.region != Region::Edge) return p;
    const ContinuousEdge edge = continuousEdge(classes, ll, temperature);
    if (edge.angleValid) {
        p.orientationDeg = edge.angleDeg;
        p.concentration = edge.concentration;
    }
    if (edge.positionValid) {
        p.offset_mm = classes.offsetOf(edge.position);
        p.position = std::clamp(static_cast<int>(std::lround(edge.position)), 1, classes.positions);
    }
    return p;
}

double perceptTemperatureFor(double setting, const Tap& tap) {
    if (setting > 0.0) return setting;
    return std::max(1, tap.sampleCount());
}

}  // namespace activetouch
