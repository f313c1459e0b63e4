#pragma once
// Shape recognition from a traced path (paper §3.4, Figure 9): a 20 x 20 histogram of tap
// locations, coordinates normalised to [0, 1] over the path's own bounding box, counts normalised
// to sum 1; templates from where a perfect edge following would tap (the outline offset outward
// to the centre of the valid range, sampled every follow step, averaged over where along the
// outline the following starts); the smallest Euclidean distance wins. The raw histogram is
// brittle (a path 1-2 mm off lands one bin away), so a smoothed histogram (Gaussian, sigma in
// bins) is offered beside it and both are reported.
#include <map>
#include <string>
#include <vector>

#include "core/geometry/Polygon.h"

namespace activetouch {

struct PathHistogram {
    int bins = 20;
    std::vector<double> cells;  ///< bins x bins, row-major from the lower left (y rows, x columns)

    double at(int ix, int iy) const { return cells[static_cast<std::size_t>(iy * bins + ix)]; }
};

/// Histogram of `points`. A degenerate extent (one point, all points equal, a straight line)
/// puts that coordinate in the middle bin. An empty path gives an all-zero histogram.
PathHistogram pathHistogram(const std::vector<Vec2>& points, int bins = 20);

/// Gaussian blur with `sigmaBins` (0 = unchanged), renormalised to sum 1.
PathHistogram smoothed(const PathHistogram& h, double sigmaBins);

double histogramDistance(const PathHistogram& a, const PathHistogram& b);

/// Where a perfect follower would tap: the outline offset outward by `offset_mm`, sampled every
/// `step_mm` along its length, the first tap `startAt_mm` along it from its first vertex.
std::vector<Vec2> idealFollowingPath(const Polygon& outline, double offset_mm, double step_mm,
                                     double startAt_mm = 0.0);

/// A shape's template: the histogram of a perfect follower's taps averaged over `phases` start
/// points spread evenly over one step. A real trial starts wherever it is placed, so its taps fall
/// at any phase along the outline; one fixed phase would make the template depend on which vertex
/// the outline lists first, and on a 4-6 mm bin that moves whole taps between bins.
PathHistogram idealFollowingHistogram(const Polygon& outline, double offset_mm, double step_mm,
                                      int bins = 20, int phases = 8);

struct ShapeTemplate {
    std::string shape;
    PathHistogram raw, smooth;
};

struct Recognition {
    std::string predicted;          ///< by the paper's rule (raw histograms)
    std::string predictedSmoothed;  ///< by the smoothed histograms
    std::map<std::string, double> distances, smoothedDistances;
    PathHistogram raw, smooth;
};

Recognition recognise(const std::vector<Vec2>& path, const std::vector<ShapeTemplate>& templates,
                      double sigmaBins);

}  // namespace activetouch
