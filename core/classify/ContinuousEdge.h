#pragma once
// An edge percept on a continuum: from one tap's log-likelihood of every class, the edge's angle
// as the posterior-weighted circular mean of the edge classes' outward normals, and its position
// across the edge as their posterior-weighted mean position, so that neither snaps to the class
// grid. Plane and air classes carry no orientation: their posterior mass is reported, not used.
#include "core/tap/ClassSet.h"

namespace activetouch {

struct ContinuousEdge {
    /// Whether the angle means anything: some edge class carries weight and the weighted
    /// normals do not cancel out (a posterior spread evenly round the circle has no mean angle).
    bool angleValid = false;
    double angleDeg = 0.0;  ///< the outward normal's angle, degrees in [0, 360)
    /// The mean resultant length of the weighted normals, in [0, 1]: 1 when one orientation takes
    /// all the edge weight, near 0 when the weight is spread round the circle.
    double concentration = 0.0;
    bool positionValid = false;  ///< some edge class carries weight
    double position = 0.0;       ///< fractional position, 1..positions (the class grid's units)
    double edgeWeight = 0.0;     ///< the posterior mass on edge classes, in [0, 1]
};

/// The continuous edge percept of one tap. `logLikelihoods` holds classes.classCount() values;
/// they are divided by `temperature` (> 0) before normalising (1: the classifier's own posterior).
/// A value of -infinity is a class ruled out; a NaN, an infinite +value, no finite value or a
/// temperature that is not positive and finite give a percept with neither part valid.
ContinuousEdge continuousEdge(const ClassSet& classes, const double* logLikelihoods,
                              double temperature = 1.0);

}  // namespace activetouch
