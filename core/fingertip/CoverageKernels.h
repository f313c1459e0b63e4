#pragma once
// The object's coverage of runs of contact-patch points near corners
// (FingertipContactModel::Contact; a single straight edge has its own loop there), written
// without branches so that several points go to an instruction, and cloned for AVX2 in the same
// operations (no FMA), so that every build gives the same coverage.
#include <cstddef>

#include "core/geometry/Vec2.h"

namespace activetouch::coverage {

/// An outline edge from a along ab, with 1 / |ab|^2.
struct Edge {
    Vec2 a, ab;
    double inverseLength2;
};

/// Points at offsets (ox, oy) from the patch centre where several outline edges come near the
/// patch (a corner, a notch): a point's side flips with each edge the segment from the centre to
/// it crosses; beyond half a cell from the nearest edge it is wholly on or off the object, within
/// it on a linear ramp.
void nearEdges(const double* ox, const double* oy, std::size_t count, Vec2 centre,
               const Edge* edges, std::size_t edgeCount, bool centreInside, double halfCell,
               float* out);

}  // namespace activetouch::coverage
