#pragma once
// Short-term memory of the perception-action loop (paper Figure 4): what the last edge was, the
// last percept that was an edge, the heading, and how many plane/air percepts came in a row.
// Updated after every decision; read by decision making and repositioning.
#include <optional>

#include "core/geometry/Vec2.h"
#include "core/validation/OfflineValidation.h"

namespace activetouch {

struct ShortTermMemory {
    double lastEdgeDeg = 270.0;          ///< outward normal of the last edge perceived (trials start on the lower edge)
    std::optional<Percept> lastEdgePercept;
    Vec2 heading{1.0, 0.0};              ///< direction of the last following move
    int planeOrAirRun = 0;               ///< consecutive plane/air percepts

    /// Remembers `percept` and, if the move followed an edge, the direction it went.
    void update(const Percept& percept, Vec2 traversal) {
        if (percept.region == Region::Edge) {
            lastEdgeDeg = percept.orientationDeg;
            lastEdgePercept = percept;
            planeOrAirRun = 0;
        } else {
            ++planeOrAirRun;
        }
        if (norm(traversal) > 0) heading = (1.0 / norm(traversal)) * traversal;
    }
};

/// Counter-clockwise traversal (object on the left): the direction along an edge whose outward
/// normal points at `normalDeg`.
inline Vec2 followDirection(double normalDeg) { return directionFromDegrees(normalDeg + 90.0); }
inline Vec2 outwardNormal(double normalDeg) { return directionFromDegrees(normalDeg); }

}  // namespace activetouch
