#pragma once
// The perceptual classes: edge orientations x positions across the edge (docs/design.md §3). Class
// index = orientation index * positions + position index. Position p (1-based) puts the tip
// centre at signed distance (p - centre) * step along the edge's outward normal, where centre =
// (positions + 1) / 2 (9.5 for the paper's 18 positions: p = 1 on the plane, p = 18 in the air).
#include <string>
#include <vector>

namespace activetouch {

/// Where a class's taps touch, computed from the fingertip geometry (plane: the whole contact
/// patch on the object; air: no taxel above the noise floor; edge: the rest).
enum class Region { Plane, Edge, Air };

const char* regionName(Region r);

struct ClassSet {
    std::vector<double> orientationsDeg{270.0, 0.0, 90.0, 180.0};  ///< outward normal angles
    int positions = 18;
    double positionStep_mm = 1.0;
    std::vector<Region> regions;  ///< per class; empty until computed from geometry

    int classCount() const { return static_cast<int>(orientationsDeg.size()) * positions; }
    int classOf(int orientationIndex, int position) const {
        return orientationIndex * positions + position - 1;
    }
    int orientationIndexOf(int cls) const { return cls / positions; }
    int positionOf(int cls) const { return cls % positions + 1; }
    double orientationDegOf(int cls) const {
        return orientationsDeg[static_cast<std::size_t>(orientationIndexOf(cls))];
    }
    /// Signed distance of the tip centre from the edge along the outward normal for position p.
    double offsetOf(double position) const {
        return (position - 0.5 * (positions + 1)) * positionStep_mm;
    }
    /// The (fractional) position whose offset is `offset_mm`.
    double positionAtOffset(double offset_mm) const {
        return offset_mm / positionStep_mm + 0.5 * (positions + 1);
    }
    Region regionOf(int cls) const {
        return regions.empty() ? Region::Edge : regions[static_cast<std::size_t>(cls)];
    }

    static std::string orientationName(double degrees);
};

/// Smallest absolute difference between two angles, degrees in [0, 180].
double angleDifferenceDeg(double a, double b);

}  // namespace activetouch
