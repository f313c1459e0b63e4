#pragma once
// Recognition at any pose (docs/general-shapes.md): a traced path is named after the library
// outline it fits best once turned and moved onto it, keeping its size, and the turn and the
// place that fit are reported with the name.
//
// Each template is an outline in its own frame, sampled every millimetre, with a grid of the
// distance to it. A path is resampled evenly along its length and centred on its centroid (the
// centroid of its length, which for a path on the outline is the outline's own); for every
// template the turn is searched every 6 degrees, the best turns are refined together with the
// position by a pattern search, and the fit is scored both ways: the path's distance to the
// outline and the outline's distance to the path (a path along part of an outline fits that
// part, not the whole). Distances are capped, so that a few taps off the contour (overshooting a
// corner) do not outweigh the rest. The score is the root mean square of the capped distances, mm.
// A template that looks the same turned by 360/k degrees reports the turn modulo that; a circle
// has no turn.
#include <string>
#include <vector>

#include "core/geometry/Polygon.h"

namespace activetouch {

struct PoseTemplate {
    std::string shape;
    std::vector<Vec2> points;  ///< the outline every ~1 mm, centred on its centroid
    Vec2 centroid;             ///< of the outline's length, in the shape's own frame
    double perimeter_mm = 0.0;
    /// Rotational symmetry: the turn is defined modulo 360 / symmetry degrees; 0 means every turn
    /// looks the same (a circle).
    int symmetry = 1;
    // Distance to the outline on a grid over its box plus a margin, centred like `points`.
    Vec2 gridOrigin;
    double cell_mm = 0.5;
    int nx = 0, ny = 0;
    std::vector<float> distance;
};

/// A template for `outline` given in the shape's own frame (not turned, placed at its origin),
/// offset outward by `offset_mm` (where the follower keeps the tip centre).
PoseTemplate poseTemplate(const std::string& shape, const Polygon& outline, double offset_mm);

struct PoseFit {
    std::string shape;
    double score_mm = 0.0;     ///< root mean square capped distance, both ways
    double rotationDeg = 0.0;  ///< the turn of the shape's frame that fits, [0, 360 / symmetry)
    Vec2 position;             ///< where the shape's frame origin lies
    int symmetry = 1;
};

struct PoseRecognition {
    bool valid = false;  ///< false for a path of fewer than 3 distinct points or no template
    std::string predicted;
    PoseFit best;
    std::vector<PoseFit> fits;  ///< every template's best fit, in the templates' order
};

PoseRecognition recognisePose(const std::vector<Vec2>& path,
                              const std::vector<PoseTemplate>& templates);

namespace detail {
/// poseTemplate() and recognisePose() with their distance grids built and read by the vector
/// units where the CPU has AVX2 and `portable` is false, one value at a time otherwise; the two
/// give bit for bit the same templates and fits.
PoseTemplate poseTemplate(const std::string& shape, const Polygon& outline, double offset_mm,
                          bool portable);
PoseRecognition recognisePose(const std::vector<Vec2>& path,
                              const std::vector<PoseTemplate>& templates, bool portable);
}  // namespace detail

/// The smallest difference between two turns of a shape with `symmetry` (0: none matters),
/// degrees in [0, 180 / symmetry].
double rotationErrorDeg(double a, double b, int symmetry);

}  // namespace activetouch
