#include "core/tap/ClassSet.h"

#include <cmath>
#include <cstdio>

namespace activetouch {

const char* regionName(Region r) {
    switch (r) {
        case Region::Plane:
            return "plane";
        case Region::Edge:
            return "edge";
        case Region::Air:
            return "air";
    }
    return "edge";
}

std::string ClassSet::orientationName(double degrees) {
    double d = std::fmod(degrees, 360.0);
    if (d < 0) d += 360.0;
    if (std::abs(d - 270.0) < 1e-9) return "lower";
    if (std::abs(d - 0.0) < 1e-9) return "right";
    if (std::abs(d - 90.0) < 1e-9) return "upper";
    if (std::abs(d - 180.0) < 1e-9) return "left";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g deg", d);
    return buf;
}

double angleDifferenceDeg(double a, double b) {
    double d = std::fmod(std::abs(a - b), 360.0);
    return d > 180.0 ? 360.0 - d : d;
}

}  // namespace activetouch
