#pragma once
// Contact physics of the ideal fingertip (docs/simulated-rig.md): the tilted rounded tip pressed
// into a compliant pad on a flat object's top face. Each taxel reads the mean indentation over its
// receptive field, counted only where the object's top face lies under the tip, so edges,
// corners and concavities come out of geometry alone.
//
// The model is pure geometry, shared by the simulated rig and by the class-region map that the
// classifier uses with any rig. It is built once; a tap costs one coverage pass over the patch
// and a few weighted sums.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/fingertip/CoverageKernels.h"
#include "core/fingertip/FingertipSpec.h"
#include "core/geometry/Polygon.h"

namespace activetouch {

class FingertipContactModel {
public:
    explicit FingertipContactModel(const FingertipSpec& spec);

    /// The model of `spec`, built once per process for the last few fingertips asked for (a
    /// sweep over seeds runs every seed on the same fingertip; building one is a twentieth of a
    /// paper seed). Thread-safe.
    static std::shared_ptr<const FingertipContactModel> shared(const FingertipSpec& spec);

    int taxelCount() const { return taxelCount_; }
    const FingertipSpec& spec() const { return spec_; }

    /// Taxel centres projected onto the contact plane, relative to the fingertip centre (the
    /// tip's first-contact point), mm.
    const std::vector<Vec2>& projectedTaxels() const { return projectedTaxels_; }

    /// Height of each taxel above the first-contact point, mm.
    const std::vector<double>& taxelHeights() const { return taxelHeights_; }

    /// Offset of the first-contact point from the mount (support axis), mm: (along heading, down).
    double firstContactForward() const { return firstContactForward_; }
    double firstContactDrop() const { return firstContactDrop_; }

    /// Body surface height above the first-contact point at a planar offset (infinite where
    /// the body never reaches within maxIndentation).
    double surfaceHeightAt(Vec2 offset) const;

    /// Half the width of the body's footprint pressed `depth` mm in (the patch points within
    /// `depth` of the first-contact point), across its narrowest direction, mm: a feature
    /// narrower than twice this lies under the footprint whichever way the finger points.
    double footprintHalfWidth(double depth) const;
    /// The contact patch of a tap centred on a long straight edge, as a radius: the footprint's
    /// half-width at the depth where the total pressure reaches `threshold` counts (`maxDepth`
    /// if it does not). What the patch spans as it follows a contour
    /// (core/geometry/ContourReach.h).
    double edgeContactRadius(double threshold, double maxDepth) const;

    /// What lies under the tip for one stage pose: the object's coverage of each patch point,
    /// computed lazily in order of surface height.
    class Contact {
    public:
        /// Total pressure (sum over taxels, counts) at indentation `depth` mm.
        double totalPressure(double depth);
        /// Indentation at which the total pressure reaches `threshold` counts, or nothing if it
        /// does not within `maxDepth`.
        std::optional<double> depthReaching(double threshold, double maxDepth);
        /// Per-taxel pressures (counts) at indentation `depth` mm into `out` (taxelCount values).
        void taxelPressures(double depth, double* out) { taxelPressuresAtDepths(&depth, 1, out); }
        /// The same at several depths, given in ascending order, into `out` (count x taxelCount):
        /// one sweep over the patch, since each taxel's pressure is d * sum(c w) - sum(c w h) over
        /// the points already pressed.
        void taxelPressuresAtDepths(const double* depths, std::size_t count, double* out);
        /// Whether every point of the patch pressed at `depth` lies on the object.
        bool patchFullyOnObject(double depth);

    private:
        friend class FingertipContactModel;
        Contact(const FingertipContactModel& model, const Polygon& object, Vec2 centre);
        /// Covers every point below `height`.
        void coverUpTo(double height);
        /// Covers points [covered_, end): their coverage, and those on the object listed.
        void coverRange(std::size_t end);

        using NearEdge = coverage::Edge;
        const FingertipContactModel* model_;
        Vec2 centre_;
        bool centreInside_ = false;
        std::vector<NearEdge> nearEdges_;  // outline edges that can reach the patch
        // The common case: one edge crossing the whole patch. A point's side and distance then
        // come from one dot product with the edge's unit normal.
        bool singleLine_ = false;
        Vec2 lineNormal_;
        double centreSide_ = 0.0;
        // Per patch point, filled in height order: points [0, covered_) have coverage, and
        // touched_ lists those of them whose coverage is not 0 (what the sums need), in order.
        std::unique_ptr<float[]> coverage_;
        std::unique_ptr<std::uint32_t[]> touched_;
        std::size_t covered_ = 0, touchedCount_ = 0;
    };

    /// The contact of the tip centred at `centre` over `object`.
    Contact contactAt(const Polygon& object, Vec2 centre) const;

private:
    struct PatchPoint {
        Vec2 offset;      // from the fingertip centre, mm
        double height;    // body surface above the first-contact point, mm
        float weightSum;  // sum over taxels of the receptive-field weights
    };
    double lowestBodyHeight(double worldX, double worldY) const;
    /// The constructor's steps: the taxels on the body surface, projected onto the plane (returns
    /// their farthest reach from the first-contact point); the patch points and their weights.
    double placeTaxels();
    void buildPatch(double reach);

    FingertipSpec spec_;
    int taxelCount_ = 0;
    std::vector<Vec2> projectedTaxels_;
    std::vector<double> taxelHeights_;
    double firstContactForward_ = 0.0, firstContactDrop_ = 0.0;
    double lowestY_ = 0.0, lowestZ_ = 0.0;  // first-contact point in the body's own world frame
    std::vector<PatchPoint> points_;        // sorted by height
    // Receptive-field weights scaled by countsPerMm, one padded row of kLanes floats per point.
    static constexpr int kLanes = 16;
    std::vector<float> weights_;
    std::vector<float> heights_;             // points_[q].height, as float for the sweep
    std::vector<double> offsetX_, offsetY_;  // points_[q].offset, one array per axis
    double patchRadius_ = 0.0;
};

}  // namespace activetouch
