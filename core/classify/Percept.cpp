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

namespace {

/// The posterior of the class scoring `top`, the largest score or within the tie tolerance of
/// it: its term, 1, over the sum of every class's e^(score - top). Classes more than 50 nats below
/// add under e^-50 each, below the sum's rounding (it is at least 1): left out, so only the few
/// near the top take an exponential.
double posteriorOf(const double* ll, int n, double top) {
    if (!std::isfinite(top)) return 0.0;
    double sum = 0.0;
    for (int c = 0; c < n; ++c)
        if (ll[c] > top - 50.0) sum += std::exp(ll[c] - top);
    return 1.0 / sum;
}

}  // namespace

Percept perceiveContinuous(const ClassSet& classes, const double* ll, double temperature) {
    const int n = classes.classCount();
    const int best = argmaxLowestIndex(ll, n);
    Percept p = perceptOf(best, posteriorOf(ll, n, ll[best]), classes);
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
