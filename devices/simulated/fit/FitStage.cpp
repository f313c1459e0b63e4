// The stage error: how far each hold lies from where it was commanded.
#include "devices/simulated/fit/FitHolds.h"

namespace activetouch::scenefit {

std::vector<double> holdOffsetsOf(const HoldModel& grid, const std::vector<TapRecord>& taps,
                                  const std::vector<char>& skip, double contactThreshold,
                                  double maxCounts, double strokeLimit) {
    std::vector<double> out(taps.size(), NAN);
    for (std::size_t i = 0; i < taps.size(); ++i) {
        // Only taps the reflex ended short of the stroke's limit: a stroke that ran to its end
        // (and a real motor may overrun it) stops where the simulated one cannot follow.
        if (taps[i].ending != TapEnding::ContactReflex ||
            (taps[i].stopDepth_mm > 0.0 && taps[i].stopDepth_mm >= strokeLimit - 1e-6))
            continue;
        const auto reading = holdReadingOf(taps[i].tap, skip, contactThreshold, maxCounts);
        if (!reading) continue;
        const std::vector<double> ones(reading->size(), 1.0), zeros(reading->size(), 0.0);
        const Vec2 pose = taps[i].pose;
        const Vec2 normal =
            grid.object().outwardNormal(grid.object().nearestOutlinePoint(pose).edge);
        auto errorAt = [&](double shift) {
            return fitDepth(*reading, grid.at(pose + normal * shift), ones, zeros).error;
        };
        double centre = 0.0;
        bool placed = true;
        for (const double step : {kOffsetStep_mm, kOffsetStep_mm / 5.0}) {
            std::vector<double> e;
            std::size_t best = 0;
            for (int j = -kOffsetSteps; j <= kOffsetSteps; ++j) {
                e.push_back(errorAt(centre + j * step));
                if (e.back() < e[best]) best = e.size() - 1;
            }
            // Best at the coarse grid's end: the hold does not place the tap within it.
            if (step == kOffsetStep_mm && (best == 0 || best + 1 == e.size())) placed = false;
            double shift = 0.0;
            if (step < kOffsetStep_mm && best > 0 && best + 1 < e.size()) {
                const double curve = e[best - 1] - 2.0 * e[best] + e[best + 1];
                if (curve > 0)
                    shift = std::clamp(0.5 * (e[best - 1] - e[best + 1]) / curve, -0.5, 0.5);
            }
            centre += (static_cast<double>(best) - kOffsetSteps + shift) * step;
        }
        if (placed) out[i] = centre;
    }
    return out;
}

OffsetSpread offsetSpread(const std::vector<double>& offsets,
                          const std::vector<std::vector<double>>& nulls, std::size_t leaveOut) {
    OffsetSpread o;
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        if (!std::isfinite(offsets[i])) continue;
        std::vector<double> v;
        for (std::size_t j = 0; j < nulls.size(); ++j)
            if (j != leaveOut) v.push_back(nulls[j][i]);
        bool all = v.size() >= 2;
        for (double x : v) all = all && std::isfinite(x);
        if (!all) continue;
        const double m = meanOf(v);
        const double var = sd(v) * sd(v);
        if (var < kLeastOffsetVariance) continue;
        o.meanSquare += (offsets[i] - m) * (offsets[i] - m) / var;
        o.expected += (1.0 + 1.0 / static_cast<double>(v.size()));
        o.precision += 1.0 / var;
        ++o.taps;
    }
    if (o.taps > 0) {
        o.meanSquare /= o.taps;
        o.expected /= o.taps;
        o.precision /= o.taps;
    }
    return o;
}

namespace {

/// The holds' offsets across the outline in recordings simulated at the recorded poses.
struct StageOffsets {
    const HoldModel& grid;
    const std::shared_ptr<const FingertipContactModel>& model;
    const std::vector<TapRecord>& recorded;
    const std::vector<char>& skip;
    double threshold, maxCounts, limit;
    std::vector<double> in(const SceneSpec& scene, std::uint64_t seed) const {
        return holdOffsetsOf(grid, simulateAt(scene, model, recorded, seed, true), skip, threshold,
                             maxCounts, limit);
    }
};

/// The stage error at which recordings simulated with `fitted` show the recorded `excess` of
/// squared offsets over `nulls` (the excess grows as the error's square: scaled over three
/// rounds of three), with its standard error.
std::pair<double, double> fitStageSigma(const StageOffsets& offsets, const SceneSpec& fitted,
                                        const std::vector<std::vector<double>>& nulls,
                                        const std::vector<double>& nullExcess, double excess,
                                        double precision, const SceneFitSettings& settings) {
    double sigma =
        std::clamp(std::sqrt(std::max(excess, 0.0) / precision), 1e-3, kMaxStageSigma_mm);
    auto excessAt = [&](double at, int count, std::uint64_t seed) {
        std::vector<double> out;
        const SceneSpec scene = withEffect(fitted, "stage_error", Json{{"sigma_mm", at}});
        for (int r = 0; r < count; ++r)
            out.push_back(
                offsetSpread(offsets.in(scene, seed + 7 * static_cast<std::uint64_t>(r)), nulls)
                    .excess());
        return out;
    };
    for (int round = 0; round < 3; ++round) {
        const double mean = meanOf(excessAt(sigma, 3, settings.seed + 96000));
        if (mean > 0)
            sigma = std::clamp(sigma * std::sqrt(std::max(excess, 0.0) / mean), 1e-3,
                               kMaxStageSigma_mm);
    }
    const auto again =
        excessAt(sigma, std::max(settings.bootstrapReplicates, 5), settings.seed + 97000);
    const double mean = meanOf(again);
    std::vector<double> sigmas;
    for (double e : again) sigmas.push_back(sigma * std::sqrt(std::max(e, 0.0) / mean));
    // Every replicate is set against the same simulated recordings of an exact stage, so their
    // spread misses what those recordings' own finite number adds to the recorded excess: the
    // spread of the excess among them, through dσ = σ dE / 2E.
    const double viaNulls = mean > 0 ? sigma * sd(nullExcess) / (2.0 * mean) : 0.0;
    return {sigma, std::hypot(sd(sigmas), viaNulls)};
}

}  // namespace

std::optional<double> readStageError(const SceneSpec& given, const SceneSpec& base,
                                     const std::shared_ptr<const FingertipContactModel>& model,
                                     const std::vector<TapRecord>& recorded,
                                     const std::vector<char>& skip, double maxCounts,
                                     const SceneFitSettings& settings, double z, SceneFit& fit) {
    // The stage's error: listed where the taps' holds lie off their commanded poses across the
    // outline by more than in recordings simulated with the fitted scene and an exact stage (the
    // drift test's form, on each tap's squared offset about its mean over those recordings, over
    // their variance there); its size then fitted by simulation, with standard errors from
    // recordings simulated at the estimate. Where the taps do not show it, the base's is kept:
    // a stage error much under the holds' own spread cannot be told from none.
    const HoldModel grid(base, *model);
    const StageOffsets offsetsOf{
        grid, model, recorded, skip, base.tap.contactThreshold, maxCounts, base.strokeLimitDepth()};
    const auto offsets =
        holdOffsetsOf(grid, recorded, skip, offsetsOf.threshold, maxCounts, offsetsOf.limit);
    // The scene as fitted: only the effects listed, at their estimates.
    const SceneSpec& fitted = fit.fitted;
    const SceneSpec exact = withEffect(fitted, "stage_error", Json());
    std::vector<std::vector<double>> nulls;
    for (int b = 0; b < std::max(settings.bootstrapReplicates, 10); ++b)
        nulls.push_back(offsetsOf.in(exact, settings.seed + 95000 + static_cast<std::uint64_t>(b)));
    const OffsetSpread spread = offsetSpread(offsets, nulls);
    std::vector<double> nullExcess;
    for (std::size_t j = 0; j < nulls.size(); ++j)
        nullExcess.push_back(offsetSpread(nulls[j], nulls, j).excess());
    const double stat = zAbove(spread.excess(), nullExcess);
    const bool listed = spread.taps >= 10 && stat > z;
    const std::string test =
        "the squared offsets across the outline of " + std::to_string(spread.taps) +
        " taps' holds (each the shift of the model's pose, its depth fitted alongside, that "
        "fits the hold best) about their means over " +
        std::to_string(nulls.size()) +
        " recordings simulated with the fitted scene and an exact stage, over their variance "
        "there, averaged, less its mean over those recordings, over its standard deviation, "
        "against the one-sided normal quantile at the level";
    if (listed) {
        const auto [sigma, se] = fitStageSigma(offsetsOf, fitted, nulls, nullExcess,
                                               spread.excess(), spread.precision, settings);
        fit.choices.push_back({"stage_error", true, test, stat, z, true});
        fit.parameters.push_back(
            {"stage_error", "sigma_mm", sigma, se, sigma - 1.96 * se, sigma + 1.96 * se});
        return sigma;
    }
    // How small a stage error the test can see: one whose excess reaches the quantile (the
    // excess grows as the error's square over each tap's variance).
    const double precision = spread.precision;
    const double smallest = precision > 0 ? std::sqrt(z * sd(nullExcess) / precision) : NAN;
    fit.choices.push_back({"stage_error", given.lists("stage_error"),
                           test + "; under it, so " +
                               (given.lists("stage_error") ? "kept as the base scene lists it"
                                                           : std::string("not listed")) +
                               " (these taps would show a stage error of about " +
                               numberText(std::round(smallest * 1000.0) / 1000.0) + " mm and more)",
                           stat, z, false});
    return std::nullopt;
}

}  // namespace activetouch::scenefit
