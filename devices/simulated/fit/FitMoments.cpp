// Noise, drift and gains by matching the moments of simulated taps at the recorded poses.
#include "devices/simulated/fit/FitParts.h"

namespace activetouch::scenefit {

bool estimatedHere(const std::string& name) {
    for (const char* e : kEstimated)
        if (name == e) return true;
    return false;
}

std::vector<double> frameTotals(const Tap& tap, const std::vector<char>& skip) {
    std::vector<double> total(static_cast<std::size_t>(tap.sampleCount()), 0.0);
    for (int t = 0; t < tap.sampleCount(); ++t)
        for (int k = 0; k < tap.taxels; ++k)
            if (!skip[static_cast<std::size_t>(k)])
                total[static_cast<std::size_t>(t)] += tap.at(t, k);
    return total;
}

double pressLevel(const std::vector<double>& total, double lowest, double highest) {
    std::vector<double> upper;
    for (double v : total)
        if (v >= lowest + 0.5 * (highest - lowest)) upper.push_back(v);
    std::nth_element(upper.begin(), upper.begin() + static_cast<long>(upper.size() / 2),
                     upper.end());
    return upper[upper.size() / 2];
}

std::vector<char> quietFrames(const Tap& tap, const std::vector<char>& skip, double margin) {
    const int T = tap.sampleCount();
    const std::vector<double> total = frameTotals(tap, skip);
    std::vector<double> sorted = total;
    const auto tenth = sorted.begin() + static_cast<long>(sorted.size() / 10);
    std::nth_element(sorted.begin(), tenth, sorted.end());
    std::vector<char> quiet(static_cast<std::size_t>(T), 0);
    for (int t = 0; t < T; ++t)
        quiet[static_cast<std::size_t>(t)] = total[static_cast<std::size_t>(t)] <= *tenth + margin;
    return quiet;
}

Moments momentsOf(const std::vector<TapRecord>& taps, const Masks& masks,
                  const std::vector<char>& skip) {
    Moments m;
    const int K = taps.empty() ? 0 : taps.front().tap.taxels;
    m.pressure.assign(static_cast<std::size_t>(K), 0.0);
    double withinSum = 0.0;
    long groups = 0;
    std::vector<std::vector<double>> means(static_cast<std::size_t>(K));
    double countSum = 0.0;
    for (std::size_t i = 0; i < taps.size(); ++i) {
        const Tap& tap = taps[i].tap;
        std::vector<char> nothing = masks.nothing[i];
        const std::vector<char> quiet = quietFrames(tap, skip, masks.quietMargin);
        for (std::size_t t = 0; t < nothing.size(); ++t) nothing[t] = nothing[t] && quiet[t];
        for (int k = 0; k < K; ++k) {
            if (skip[static_cast<std::size_t>(k)]) continue;
            double s = 0.0, s2 = 0.0;
            int n = 0;
            for (int t = 0; t < tap.sampleCount(); ++t) {
                const double v = tap.at(t, k);
                if (nothing[static_cast<std::size_t>(t)]) {
                    s += v;
                    s2 += v * v;
                    ++n;
                } else if (masks.pressed[i][static_cast<std::size_t>(t * K + k)]) {
                    m.pressure[static_cast<std::size_t>(k)] += v;
                }
            }
            if (n >= 3) {
                const double mean = s / n;
                withinSum += (s2 - n * mean * mean) / (n - 1);
                ++groups;
                means[static_cast<std::size_t>(k)].push_back(mean);
                countSum += n;
            }
            m.nothing += n;
        }
    }
    if (groups == 0) return m;
    m.within = withinSum / static_cast<double>(groups);
    double between = 0.0;
    long count = 0;
    for (const auto& list : means) {
        if (list.size() < 2) continue;
        const double mean = std::accumulate(list.begin(), list.end(), 0.0) / list.size();
        for (double v : list) between += (v - mean) * (v - mean);
        count += static_cast<long>(list.size()) - 1;
    }
    const double meanCount = countSum / static_cast<double>(groups);
    m.wander = count > 0 ? between / count - m.within / meanCount : 0.0;
    return m;
}

SceneSpec sceneWith(const SceneSpec& base, const Theta& th, bool quantised, double maxCounts,
                    const std::vector<int>& dead, double deadReading,
                    const EffectSpec* driftTemplate, const EffectSpec* blink) {
    SceneSpec s = base;
    std::vector<EffectSpec> kept;
    for (const auto& e : base.effects)
        if (!estimatedHere(e.name)) kept.push_back(e);
    auto add = [&](const std::string& name, Json parameters) {
        EffectSpec e;
        e.name = name;
        e.parameters = std::move(parameters);
        e.place = "/effects/" + std::to_string(kept.size());
        kept.push_back(std::move(e));
    };
    bool gained = false;
    for (double g : th.gains) gained = gained || g != 1.0;
    if (gained) add("taxel_gain", Json{{"gains", th.gains}});
    if (!dead.empty()) add("dead_taxel", Json{{"taxels", dead}, {"reading_counts", deadReading}});
    if (blink) add(blink->name, blink->parameters);
    if (th.rate > 0) {
        Json p =
            driftTemplate
                ? driftTemplate->parameters
                : Json{{"touch_threshold_counts", 2.0}, {"free_gain", 0.2}, {"touch_gain", 0.05}};
        p["rate_counts_per_sqrt_s"] = th.rate;
        add("baseline_drift", p);
    }
    if (th.sigma > 0) add("taxel_noise", Json{{"sigma_counts", th.sigma}});
    if (quantised) add("adc_quantisation", Json{{"max_counts", maxCounts}});
    s.effects = kept;
    return s;
}

std::vector<TapRecord> simulateAt(const SceneSpec& scene,
                                  const std::shared_ptr<const FingertipContactModel>& model,
                                  const std::vector<TapRecord>& at, std::uint64_t seed,
                                  bool strokes) {
    SceneSpec s = scene;
    s.seed = seed;
    SimulatedWorld world(s, model);
    std::vector<TapRecord> out;
    out.reserve(at.size());
    for (const auto& r : at) {
        world.moveStage(r.pose);
        if (strokes && r.ending == TapEnding::ContactReflex && r.stopDepth_mm > 0.0)
            world.stopNextTapAt(r.stopDepth_mm);
        out.push_back(world.tap());
    }
    return out;
}

Theta fitMoments(const FitContext& c, const Moments& target, std::uint64_t seed) {
    const int K = static_cast<int>(c.skip.size());
    Theta th;
    th.sigma = std::sqrt(std::max(target.within, 0.0));
    th.rate = target.wander > 0 ? 0.5 : 0.0;
    th.gains.assign(static_cast<std::size_t>(K), 1.0);
    for (int round = 0; round < c.iterations; ++round) {
        const SceneSpec s = sceneWith(c.base, th, c.quantised, c.maxCounts, c.dead, c.deadReading,
                                      c.driftTemplate, c.blink);
        // The moments of a few simulations, averaged: one simulation's own drift and noise
        // would pull every round's estimate the same way.
        Moments m;
        for (int r = 0; r < c.simulations; ++r) {
            const Moments one = momentsOf(
                simulateAt(s, c.model, c.poses, seed + 7919 * static_cast<std::uint64_t>(r)),
                c.masks, c.skip);
            if (r == 0) {
                m = one;
            } else {
                m.within += one.within;
                m.wander += one.wander;
                for (std::size_t k = 0; k < m.pressure.size(); ++k)
                    m.pressure[k] += one.pressure[k];
            }
        }
        m.within /= c.simulations;
        m.wander /= c.simulations;
        for (double& p : m.pressure) p /= c.simulations;
        if (th.sigma > 0 && m.within > 0)
            th.sigma *= std::sqrt(std::clamp(target.within / m.within, 0.25, 4.0));
        if (target.wander <= 0) {
            th.rate = 0.0;
        } else if (m.wander > 0) {
            th.rate = std::max(th.rate, 1e-3) *
                      std::sqrt(std::clamp(target.wander / m.wander, 0.25, 4.0));
        } else {
            th.rate = std::max(2.0 * th.rate, 0.05);
        }
        for (int k = 0; k < K; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            if (c.skip[kk] || m.pressure[kk] <= 0 || target.pressure[kk] <= 0) continue;
            th.gains[kk] =
                std::clamp(th.gains[kk] * target.pressure[kk] / m.pressure[kk], 0.05, 20.0);
        }
    }
    return th;
}

}  // namespace activetouch::scenefit
