#include "core/classify/Percept.h"

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

}  // namespace activetouch
