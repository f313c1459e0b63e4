// Crosstalk: pressure coupled from pressed taxels into their neighbours during the holds.
#include "devices/simulated/fit/FitHolds.h"

namespace activetouch::scenefit {

std::vector<std::pair<int, int>> couplingPairs(const FingertipContactModel& model,
                                               double radius_mm) {
    const auto& p = model.projectedTaxels();
    std::vector<std::pair<int, int>> pairs;
    for (int i = 0; i < model.taxelCount(); ++i)
        for (int j = 0; j < model.taxelCount(); ++j)
            if (i != j && distance(p[static_cast<std::size_t>(i)],
                                   p[static_cast<std::size_t>(j)]) <= radius_mm)
                pairs.push_back({i, j});
    return pairs;
}

double holdCoupling(const std::vector<Hold>& holds, const std::vector<int>& which, int K,
                    const std::vector<std::pair<int, int>>& pairs) {
    const auto KK = static_cast<std::size_t>(K);
    std::vector<double> gain(KK, 1.0), offset(KK, 0.0);
    double c = 0.0;
    std::vector<double> own(which.size() * KK), near(which.size() * KK);
    std::vector<double> coupled;
    for (int round = 0; round < 4; ++round) {
        for (std::size_t n = 0; n < which.size(); ++n) {
            const Hold& h = holds[static_cast<std::size_t>(which[n])];
            const std::size_t D = h.modelAtDepths.size() / KK;
            std::vector<double> neighbours(h.modelAtDepths.size(), 0.0);
            for (std::size_t d = 0; d < D; ++d)
                for (const auto& [to, from] : pairs)
                    neighbours[d * KK + static_cast<std::size_t>(to)] +=
                        h.modelAtDepths[d * KK + static_cast<std::size_t>(from)];
            coupled.resize(h.modelAtDepths.size());
            for (std::size_t i = 0; i < coupled.size(); ++i)
                coupled[i] = h.modelAtDepths[i] + c * neighbours[i];
            const DepthFit f = fitDepth(h.reading, coupled, gain, offset);
            for (std::size_t k = 0; k < KK; ++k) {
                own[n * KK + k] = f.at(h.modelAtDepths, KK, k);
                near[n * KK + k] = f.at(neighbours, KK, k);
            }
        }
        auto used = [&](std::size_t n, std::size_t k) {
            const double r = holds[static_cast<std::size_t>(which[n])].reading[k];
            return std::isfinite(r) && (own[n * KK + k] > kPressed || near[n * KK + k] > kPressed);
        };
        for (std::size_t k = 0; k < KK; ++k) {
            LineFit line;
            for (std::size_t n = 0; n < which.size(); ++n)
                if (used(n, k))
                    line.add(own[n * KK + k] + c * near[n * KK + k],
                             holds[static_cast<std::size_t>(which[n])].reading[k]);
            const double g = line.gain();
            gain[k] = g > 0 ? g : 1.0;
            offset[k] = g > 0 ? line.offset(g) : 0.0;
        }
        double num = 0.0, den = 0.0;
        for (std::size_t n = 0; n < which.size(); ++n)
            for (std::size_t k = 0; k < KK; ++k) {
                if (!used(n, k)) continue;
                const double r = holds[static_cast<std::size_t>(which[n])].reading[k];
                const double y = r - offset[k] - gain[k] * own[n * KK + k];
                const double x = gain[k] * near[n * KK + k];
                num += x * y;
                den += x * x;
            }
        c = den > 0 ? std::clamp(num / den, -kMaxCoupling, kMaxCoupling) : 0.0;
    }
    return c;
}

Coupling couplingOf(const std::vector<Hold>& holds, int K,
                    const std::vector<std::pair<int, int>>& pairs, int replicates,
                    std::uint64_t seed) {
    Coupling c;
    c.holds = static_cast<int>(holds.size());
    if (holds.size() < 10 || pairs.empty()) return c;
    const std::vector<int> all = everyIndex(holds.size());
    c.value = holdCoupling(holds, all, K, pairs);
    RandomStream rng(seed);
    std::vector<int> pick;
    std::vector<double> reps;
    for (int b = 0; b < replicates; ++b) {
        resampleRuns(rng, holds.size(), pick);
        reps.push_back(holdCoupling(holds, pick, K, pairs));
    }
    c.se = sd(reps);
    return c;
}

SceneSpec readCrosstalk(const SceneSpec& given, SceneSpec base,
                        const std::shared_ptr<const FingertipContactModel>& model,
                        const std::vector<TapRecord>& recorded, const std::vector<char>& skip,
                        double maxCounts, const SceneFitSettings& settings, double z,
                        SceneFit& fit) {
    const int K = model->taxelCount();
    // Crosstalk, from the holds of the bare contact (the base's own coupling left out): listed
    // where the common coupling lies more than the quantile of its standard errors above zero,
    // and then put in the scene every simulation below takes, at the base's radius (or the
    // effect's default).
    {
        double radius = kDefaultCouplingRadius_mm;
        for (const auto& e : given.effects)
            if (e.name == "crosstalk") radius = e.parameters.value("radius_mm", radius);
        const auto pairs = couplingPairs(*model, radius);
        const Coupling coupling =
            couplingOf(holdsOf(base, *model, recorded, skip, maxCounts, false), K, pairs,
                       settings.holdReplicates, settings.seed + 98000);
        const double stat = coupling.se > 0 ? coupling.value / coupling.se : 0.0;
        const bool listed = coupling.holds >= 10 && stat > z;
        // The taxels' own lines take much of a coupling (a taxel with more neighbours reads
        // more throughout), so the holds read it low, and lower still for a small one: the
        // coupling is the one at which taps simulated at the recorded poses read as the recorded
        // ones do (by the secant from 0.02 and 0.1, three steps, two simulations each, the same
        // seeds throughout), and its error goes through the same slope.
        double value = coupling.value, se = coupling.se;
        if (listed) {
            auto shownAt = [&](double c) {
                double shown = 0.0;
                for (int r = 0; r < 2; ++r) {
                    const auto taps = simulateAt(
                        withEffect(base, "crosstalk", Json{{"coupling", c}, {"radius_mm", radius}}),
                        model, recorded, settings.seed + 99000 + static_cast<std::uint64_t>(r));
                    const auto holds = holdsOf(base, *model, taps, skip, maxCounts, false);
                    const std::vector<int> all = everyIndex(holds.size());
                    shown += holdCoupling(holds, all, K, pairs) / 2.0;
                }
                return shown;
            };
            double c0 = 0.02, c1 = 0.1, s0 = shownAt(c0), s1 = shownAt(c1);
            for (int step = 0; step < 3 && s1 != s0; ++step) {
                const double c2 = std::clamp(c1 + (coupling.value - s1) * (c1 - c0) / (s1 - s0),
                                             1e-4, kMaxCoupling);
                c0 = c1;
                s0 = s1;
                c1 = c2;
                s1 = shownAt(c1);
            }
            const double slope = c1 != c0 ? (s1 - s0) / (c1 - c0) : 0.0;
            value = c1;
            se = slope > 0 ? coupling.se / slope : coupling.se;
        }
        fit.choices.push_back(
            {"crosstalk", listed,
             "the coupling read from " + std::to_string(coupling.holds) +
                 " taps' holds (each taxel's reading a line in its own pressure plus the coupling "
                 "times its neighbours' within " +
                 numberText(radius) +
                 " mm, each hold's depth fitted) over its standard error from resampling the taps, "
                 "against the one-sided normal quantile at the level",
             stat, z, true});
        if (listed)
            fit.parameters.push_back(
                {"crosstalk", "coupling", value, se, value - 1.96 * se, value + 1.96 * se});
        base = withEffect(base, "crosstalk",
                          listed ? Json{{"coupling", value}, {"radius_mm", radius}} : Json());
    }

    return base;
}

}  // namespace activetouch::scenefit
