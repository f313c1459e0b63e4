#pragma once
// Short-term memory of the perception-action loop (paper Figure 4): what the last edge was, the
// last percept that was an edge, the heading, and how many plane/air percepts came in a row.
// Updated after every decision; read by decision making and repositioning.
#include <cmath>
#include <optional>
#include <vector>

#include "core/classify/Percept.h"
#include "core/geometry/Vec2.h"

namespace activetouch {

struct ShortTermMemory {
    double lastEdgeDeg =
        270.0;  ///< outward normal of the last confirmed edge (trials start on the lower edge)
    std::optional<Percept> lastEdgePercept;
    Vec2 heading{1.0, 0.0};       ///< direction of travel along the last confirmed edge
    int planeOrAirRun = 0;        ///< consecutive percepts without a usable edge
    int confirmationsNeeded = 1;  ///< same-orientation edge percepts in a row that confirm an edge
    double candidateEdgeDeg = 270.0;
    int candidateRun = 0;
    /// Edge angles this close (degrees) count as the same edge; 0 for class orientations, which
    /// are equal or not.
    double sameEdgeToleranceDeg = 0.0;

    /// The recent usable edge percepts, where they were taken: the contour's turn per mm comes
    /// from them (continuous percept). A tap without a usable edge clears them, since a corner
    /// may lie between.
    struct EdgeSample {
        Vec2 pose;
        double angleDeg;
    };
    std::vector<EdgeSample> recentEdges;

    /// Remembers an edge angle at `pose`, keeping the last `keep`.
    void noteEdgeAt(Vec2 pose, double angleDeg, int keep) {
        recentEdges.push_back({pose, angleDeg});
        if (static_cast<int>(recentEdges.size()) > keep)
            recentEdges.erase(recentEdges.begin(),
                              recentEdges.end() - static_cast<std::ptrdiff_t>(keep));
    }

    /// The contour's turn in degrees per mm travelled over the recent edges (positive turning
    /// left, counter-clockwise), or 0 with fewer than two or no distance between them.
    double turnDegPerMm() const {
        double turn = 0.0, travelled = 0.0;
        for (std::size_t i = 1; i < recentEdges.size(); ++i) {
            double d = std::fmod(recentEdges[i].angleDeg - recentEdges[i - 1].angleDeg, 360.0);
            if (d > 180.0) d -= 360.0;
            if (d <= -180.0) d += 360.0;
            turn += d;
            travelled += distance(recentEdges[i].pose, recentEdges[i - 1].pose);
        }
        return travelled > 1e-9 ? turn / travelled : 0.0;
    }

    /// Remembers `percept` (an edge only if its orientation was usable). An edge becomes the
    /// last edge, and its direction the heading, once it has been perceived
    /// `confirmationsNeeded` times in a row: one misperceived tap then cannot redirect the
    /// plane and air rules, which act on memory alone.
    void update(const Percept& percept, bool usableEdge) {
        if (!usableEdge) {
            ++planeOrAirRun;
            candidateRun = 0;
            recentEdges.clear();
            return;
        }
        planeOrAirRun = 0;
        if (candidateRun > 0 && sameEdge(percept.orientationDeg, candidateEdgeDeg)) {
            ++candidateRun;
        } else {
            candidateEdgeDeg = percept.orientationDeg;
            candidateRun = 1;
        }
        if (candidateRun >= confirmationsNeeded) {
            lastEdgeDeg = percept.orientationDeg;
            lastEdgePercept = percept;
            heading = directionFromDegrees(percept.orientationDeg + 90.0);
        }
    }

private:
    bool sameEdge(double a, double b) const {
        if (sameEdgeToleranceDeg <= 0.0) return a == b;
        return angleDifferenceDeg(a, b) <= sameEdgeToleranceDeg;
    }
};

/// Counter-clockwise traversal (object on the left): the direction along an edge whose outward
/// normal points at `normalDeg`.
inline Vec2 followDirection(double normalDeg) {
    return directionFromDegrees(normalDeg + 90.0);
}
inline Vec2 outwardNormal(double normalDeg) {
    return directionFromDegrees(normalDeg);
}

}  // namespace activetouch
