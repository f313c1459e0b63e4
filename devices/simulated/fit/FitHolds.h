#pragma once
// The holds of touching taps: each pressed reading against the model at the depth it held, and
// the gains, stage error and crosstalk read from them (FitGains.cpp, FitStage.cpp,
// FitCrosstalk.cpp). Internal to devices/simulated.
#include "core/stats/Intervals.h"
#include "devices/simulated/fit/FitParts.h"

namespace activetouch::scenefit {

/// The taxels' sensitivities relative to one another, read from the holds alone so that a stroke
/// on another schedule or to another depth than the scene's reads the same (see fitScene()).
struct HoldGains {
    std::vector<double> logGain, se;  ///< per taxel, about their plain mean; se 0 = not read
    int taps = 0;                     ///< touching taps whose hold was read
    double q = 0.0;                   ///< Cochran's Q of the log gains
    int df = 0;                       ///< taxels read
};

inline constexpr double kHoldShare = 0.95;

/// A touching tap's press as its own frames show it, whatever the stroke's schedule: the totals
/// over the live taxels; the press's level, the median total of the frames above half the range
/// (most of which are the hold's: a pad with memory reads above it for a frame after release);
/// the hold, the frames from the first within 5 % of that level (above the lowest total); and
/// the quiet frames before the hold, within 3 % of the range above the lowest, where a baseline
/// is read before contact (after release a pad with memory, or a baseline compensation that
/// followed the press, reads otherwise).
struct Press {
    std::vector<double> total;
    double lowest = 0.0, level = 0.0;
    int first = 0, last = 0;  ///< the hold's first and last frame
    std::vector<int> quiet;
    bool inHold(int t) const {
        return std::abs(total[static_cast<std::size_t>(t)] - level) <=
               (1.0 - kHoldShare) * (level - lowest);
    }
};

/// The press of `tap`, or nothing for a tap that did not touch (its range of totals under half
/// the reflex's threshold) or has fewer than two quiet frames before its hold.

std::optional<Press> pressOf(const Tap& tap, const std::vector<char>& skip,
                             double contactThreshold);

/// A touching tap's hold: each taxel's median over the frames of the hold, less its baseline
/// before contact, and the model's pressures at the tap's pose over a grid of depths to the
/// stroke's limit.
struct Hold {
    std::vector<double> reading;        ///< per taxel; NaN where unusable (saturated)
    std::vector<double> modelAtDepths;  ///< [depth][taxel]
};

inline constexpr int kHoldDepths = 120;

/// The hold's readings of `tap` (see Hold), or nothing for a tap without a press.

std::optional<std::vector<double>> holdReadingOf(const Tap& tap, const std::vector<char>& skip,
                                                 double contactThreshold, double maxCounts);

/// The noise-free model's pressures for holds: at a pose, over the grid of depths to the stroke's
/// limit, with the coupling the base scene lists (it acts on every frame before the gains, so the
/// model's pressures carry it too, through the scene's own effect, the depths taken as frames).
class HoldModel {
public:
    /// With `coupled` false, the bare contact's pressures (the base's crosstalk left out).
    HoldModel(const SceneSpec& base, const FingertipContactModel& model, bool coupled = true)
        : model_(model), object_(base.object.outline()), depths_(kHoldDepths) {
        for (const auto& e : base.effects)
            if (coupled && e.name == "crosstalk")
                crosstalk_ = findEffect(e.name)->make(
                    JsonFields(e.parameters, base.source, e.place), model, RandomStream());
        const double stroke = base.strokeLimitDepth();
        for (int d = 0; d < kHoldDepths; ++d)
            depths_[static_cast<std::size_t>(d)] = stroke * (d + 1) / kHoldDepths;
    }
    /// [depth][taxel]
    std::vector<double> at(Vec2 pose) const {
        auto contact = model_.contactAt(object_, pose);
        Tap grid(kHoldDepths, model_.taxelCount());
        contact.taxelPressuresAtDepths(depths_.data(), depths_.size(), grid.samples.data());
        if (crosstalk_) crosstalk_->shapeSignal(grid, SignalContext{});
        return std::move(grid.samples);
    }
    const Polygon& object() const { return object_; }

private:
    const FingertipContactModel& model_;
    Polygon object_;
    std::vector<double> depths_;
    std::unique_ptr<Effect> crosstalk_;
};

std::vector<Hold> holdsOf(const SceneSpec& base, const FingertipContactModel& model,
                          const std::vector<TapRecord>& recorded, const std::vector<char>& skip,
                          double maxCounts, bool coupled = true);

/// The depth at which the model's pressures (`modelAtDepths`, [depth][taxel]) fit a hold's
/// readings best with the taxels' lines (reading = offset + gain x model): the grid point, the
/// shift towards a neighbour (-0.5..0.5 grid steps) of the parabola through it and its
/// neighbours, and the squared error there.
struct DepthFit {
    std::size_t best = 0, depths = 0;
    double shift = 0.0, error = 0.0;
    /// `grid` ([depth][taxel], `taxels` wide) for `taxel` at the fitted depth, between the grid
    /// point and its neighbour towards the shift.
    double at(const std::vector<double>& grid, std::size_t taxels, std::size_t taxel) const {
        const std::size_t other = shift < 0 ? best - 1 : std::min(best + 1, depths - 1);
        const double w = std::abs(shift);
        return (1.0 - w) * grid[best * taxels + taxel] + w * grid[other * taxels + taxel];
    }
};

/// A taxel's line, reading = offset + gain x model, by least squares over the points added; no
/// line (gain 0) from fewer than five points or a model that does not vary.
struct LineFit {
    double n = 0.0, sx = 0.0, sr = 0.0, sxx = 0.0, sxr = 0.0;
    void add(double x, double r) {
        n += 1.0;
        sx += x;
        sr += r;
        sxx += x * x;
        sxr += x * r;
    }
    double gain() const {
        const double spread = sxx - sx * sx / std::max(n, 1.0);
        return n >= 5 && spread > 0 ? (sxr - sx * sr / n) / spread : 0.0;
    }
    double offset(double g) const { return (sr - g * sx) / n; }
};

/// 0, 1, ..., count - 1: every entry, in order.

std::vector<int> everyIndex(std::size_t count);

/// Runs of ten consecutive entries of `count`, each starting where `rng` says, into `pick` (as
/// many as `count`): a resampling that keeps neighbours together (a drifting baseline ties
/// consecutive taps).

void resampleRuns(RandomStream& rng, std::size_t count, std::vector<int>& pick);

DepthFit fitDepth(const std::vector<double>& reading, const std::vector<double>& modelAtDepths,
                  const std::vector<double>& gain, const std::vector<double>& offset);

/// The grid the hold offsets are read on: this many steps each way of kOffsetStep_mm, then
/// kOffsetSteps each way of a fifth of that about the best.
inline constexpr int kOffsetSteps = 6;

inline constexpr double kOffsetStep_mm = 0.05;

/// How far each tap lies off its commanded pose across the outline, as its hold shows it: the
/// shift along the outward normal of the outline's nearest edge at which the noise-free model,
/// its depth fitted alongside, fits the hold's readings best (the parabola through the best of a
/// fine grid about the best of a coarse one); NaN for a tap without a hold, one the reflex did not
/// end short of the stroke's limit, and one whose hold the coarse grid does not bracket.

std::vector<double> holdOffsetsOf(const HoldModel& grid, const std::vector<TapRecord>& taps,
                                  const std::vector<char>& skip, double contactThreshold,
                                  double maxCounts, double strokeLimit);

/// A tap whose offset varies less than this (mm squared) over recordings at its pose is not read:
/// its hold does not place it (the fit sits at the grid's end, or the model does not change).
inline constexpr double kLeastOffsetVariance = 1e-8;

/// The largest stage error the effect takes, mm.
inline constexpr double kMaxStageSigma_mm = 2.0;

/// The spread of `offsets` about their means over `nulls` (recordings simulated at the same
/// poses with an exact stage; `leaveOut` of them left out), over the taps every one of them read
/// and places: the mean over taps of the squared offset about its mean there over its variance
/// there, and what that mean is under an exact stage (1 + 1/their count).
struct OffsetSpread {
    double meanSquare = 0.0, expected = 0.0;
    double precision = 0.0;  ///< the taps' inverse variance there, averaged
    int taps = 0;
    double excess() const { return meanSquare - expected; }
};

OffsetSpread offsetSpread(const std::vector<double>& offsets,
                          const std::vector<std::vector<double>>& nulls,
                          std::size_t leaveOut = static_cast<std::size_t>(-1));

/// Log gains (about their plain mean) from the holds picked by `which`: alternately each hold's
/// depth (the grid point, refined by a parabola, that fits its readings best with the taxels'
/// lines so far) and each taxel's line, reading = offset + gain x model, by least squares over
/// the holds that press it over kPressed counts at their depth. The offset takes what a baseline
/// under zero hides: a skin that clamps its readings at zero reads nothing over nothing whether
/// its baseline lies a little below or at zero, but a press shows the difference. NaN for a
/// taxel fewer than five holds press so.

std::vector<double> holdLogGains(const std::vector<Hold>& holds, const std::vector<int>& which,
                                 int K);

/// The pairs (reader, neighbour) the crosstalk effect couples at `radius_mm`, as it takes them.

std::vector<std::pair<int, int>> couplingPairs(const FingertipContactModel& model,
                                               double radius_mm);

/// The crosstalk's coupling as the holds picked by `which` show it (holds of the bare contact):
/// each taxel reads offset + gain x (its own pressure + c x its neighbours'), alternately each
/// hold's depth (fitDepth() on those pressures), each taxel's line by least squares over the
/// holds that press it or its neighbours over kPressed counts at their depth, and the common c,
/// four rounds from c = 0.

double holdCoupling(const std::vector<Hold>& holds, const std::vector<int>& which, int K,
                    const std::vector<std::pair<int, int>>& pairs);

/// The coupling with its standard error from resampling runs of ten consecutive holds.
struct Coupling {
    double value = 0.0, se = 0.0;
    int holds = 0;
};

Coupling couplingOf(const std::vector<Hold>& holds, int K,
                    const std::vector<std::pair<int, int>>& pairs, int replicates,
                    std::uint64_t seed);

HoldGains holdGains(const std::vector<Hold>& holds, int K, int replicates, std::uint64_t seed);

/// The reflex's latency, read first, from the stroke's own travel (see the comment inside): its
/// choice and estimate into `fit`, and the scene every later simulation takes (`given` with the
/// latency read, or as it is where the recording holds too few stop depths).

SceneSpec readCrosstalk(const SceneSpec& given, SceneSpec base,
                        const std::shared_ptr<const FingertipContactModel>& model,
                        const std::vector<TapRecord>& recorded, const std::vector<char>& skip,
                        double maxCounts, const SceneFitSettings& settings, double z,
                        SceneFit& fit);

/// The stage's error (see the comment inside), against `fit.fitted` as fitted so far: its
/// choice and estimate into `fit`, and the error read, where the taps show one.

std::optional<double> readStageError(const SceneSpec& given, const SceneSpec& base,
                                     const std::shared_ptr<const FingertipContactModel>& model,
                                     const std::vector<TapRecord>& recorded,
                                     const std::vector<char>& skip, double maxCounts,
                                     const SceneFitSettings& settings, double z, SceneFit& fit);

}  // namespace activetouch::scenefit
