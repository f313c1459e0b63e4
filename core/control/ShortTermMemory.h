#pragma once
// Short-term memory of the perception-action loop (paper Figure 4): what the last edge was, the
// last percept that was an edge, the heading, and how many plane/air percepts came in a row.
// Updated after every decision; read by decision making and repositioning.
#include <optional>

#include "core/geometry/Vec2.h"
#include "core/classify/Percept.h"

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

    /// Remembers `percept` (an edge only if its orientation was usable). An edge becomes the
    /// last edge, and its direction the heading, once it has been perceived
    /// `confirmationsNeeded` times in a row: one misperceived tap then cannot redirect the
    /// plane and air rules, which act on memory alone.
    void update(const Percept& percept, bool usableEdge) {
        if (!usableEdge) {
            ++planeOrAirRun;
            candidateRun = 0;
            return;
        }
        planeOrAirRun = 0;
        if (candidateRun > 0 && percept.orientationDeg == candidateEdgeDeg) {
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
