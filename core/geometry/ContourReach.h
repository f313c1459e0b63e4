#pragma once
// What a round contact patch can resolve of an outline (docs/general-shapes.md §What the fingertip
// can resolve): the object closed and opened by a disc of the patch's radius. A contour point is
// within reach when a disc of that radius lying wholly off the object comes within the tolerance
// of it (so the patch can press against it from outside: no notch, gap or inside corner narrower
// than the patch hides it) and a disc lying wholly on the object does too (no tooth, spike or
// outside corner thinner than the patch carries it). The contour is sampled every half
// millimetre, as the following measures coverage.
#include <cstddef>
#include <memory>
#include <vector>

#include "core/geometry/Polygon.h"

namespace activetouch {

/// A stretch of contour the patch cannot resolve.
struct OutOfReach {
    enum class Kind {
        Inward,   ///< a notch, a gap between teeth, an inside corner: the patch cannot get in
        Outward,  ///< a tooth, a spike, an outside corner: the patch covers it whole
    };
    Kind kind = Kind::Inward;
    double fromArc_mm = 0.0;  ///< where it starts, along the contour from vertex 0
    double length_mm = 0.0;   ///< contour length out of reach
    double mouth_mm = 0.0;    ///< straight distance between its two ends (a notch's mouth)
    /// The farthest the rolling disc stays from any of its points, mm; `depthCapped` where it is
    /// at least this (the search stops at twice the radius).
    double depth_mm = 0.0;
    bool depthCapped = false;
    Vec2 middle;  ///< the contour point halfway along it
};

class ContourReach {
public:
    /// Samples `outline` every half millimetre (fewer, evenly, past kMaxSamples) and rolls a disc
    /// of `radius_mm` round it outside and inside; a radius of 0 reaches everything.
    ContourReach(const Polygon& outline, double radius_mm);
    /// The same, kept for the process: reach depends on the outline and the radius alone, and
    /// every trial of an object at one pose (over every seed, whichever thread runs it) and the
    /// run's cautions ask for the same one, so it is worked out once. Safe from any thread.
    static std::shared_ptr<const ContourReach> shared(const Polygon& outline, double radius_mm);

    static constexpr double kStep_mm = 0.5;
    static constexpr std::size_t kMaxSamples = 20000;

    /// How many contour points were judged: ceil(perimeter / kStep_mm), at most kMaxSamples.
    static std::size_t sampleCount(double perimeter_mm);

    std::size_t samples() const { return reachable_.size(); }
    /// Whether sample i (at arc i * perimeter / samples) lies within the patch's reach.
    bool reachable(std::size_t i) const { return reachable_[i] != 0; }
    double reachableFraction() const;
    /// The stretches out of reach, in contour order from vertex 0.
    const std::vector<OutOfReach>& stretches() const { return stretches_; }
    double radius_mm() const { return radius_; }
    /// How far a point may lie from the rolling disc and still count as reached: half the radius,
    /// so that a right-angled corner (whose tip a disc misses by 0.41 radii) is within reach.
    double tolerance_mm() const { return 0.5 * radius_; }

private:
    void collectStretches(const Polygon& outline, const std::vector<Vec2>& points,
                          const std::vector<double>& inwardGap,
                          const std::vector<double>& outwardGap);

    double radius_ = 0.0;
    std::vector<char> reachable_;
    std::vector<OutOfReach> stretches_;
};

}  // namespace activetouch
