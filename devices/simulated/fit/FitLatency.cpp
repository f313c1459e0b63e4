// The reflex latency and the skin's memory, from where strokes stopped and how taps end.
#include "devices/simulated/fit/FitHolds.h"

namespace activetouch::scenefit {

Tail tailOf(const std::vector<TapRecord>& taps, const std::vector<char>& skip,
            double contactThreshold) {
    Tail tail;
    for (const auto& r : taps) {
        const int T = r.tap.sampleCount();
        const auto press = pressOf(r.tap, skip, contactThreshold);
        if (!press) continue;
        const auto& raw = press->total;
        std::vector<double> quiet;
        for (int t : press->quiet) quiet.push_back(raw[static_cast<std::size_t>(t)]);
        const double base = stats::medianOr(std::move(quiet), std::nan(""));
        const double pressed = press->level - base;
        if (pressed <= 0) continue;
        int end = -1;
        for (int t = press->last + 1; t < T && end < 0; ++t) {
            const double v = raw[static_cast<std::size_t>(t)] - base;
            const double drop =
                raw[static_cast<std::size_t>(t - 1)] - raw[static_cast<std::size_t>(t)];
            if (v < 0.5 * pressed && drop < 0.05 * pressed) end = t;
        }
        if (end < 0 || end + kTailFrames > T) continue;
        double early = 0.0, late = 0.0;
        for (int j = 0; j < 3; ++j)
            early += (raw[static_cast<std::size_t>(end + j)] - base) / pressed;
        for (int j = 6; j < kTailFrames; ++j)
            late += (raw[static_cast<std::size_t>(end + j)] - base) / pressed;
        tail.early += early / 3.0;
        tail.late += late / (kTailFrames - 6);
        ++tail.taps;
    }
    if (tail.taps > 0) {
        tail.early /= tail.taps;
        tail.late /= tail.taps;
    }
    return tail;
}

SceneSpec withEffect(const SceneSpec& scene, const std::string& name, const Json& parameters) {
    SceneSpec s = scene;
    std::vector<EffectSpec> effects;
    for (const auto& e : scene.effects)
        if (e.name != name) effects.push_back(e);
    if (!parameters.is_null()) {
        EffectSpec e;
        e.name = name;
        e.parameters = parameters;
        e.place = "/effects/" + std::to_string(effects.size());
        effects.push_back(std::move(e));
    }
    s.effects = std::move(effects);
    return s;
}

SceneSpec withMemory(const SceneSpec& scene, double fraction, double tau) {
    return withEffect(
        scene, "viscoelastic_memory",
        fraction > 0 ? Json{{"fraction", fraction}, {"time_constant_s", tau}} : Json());
}

SceneSpec withLatency(const SceneSpec& scene, double latency_s) {
    return withEffect(scene, "contact_latency",
                      latency_s > 0 ? Json{{"latency_s", latency_s}} : Json());
}

std::vector<double> crossingsOf(const SceneSpec& scene, const FingertipContactModel& model,
                                const std::vector<TapRecord>& taps) {
    const Polygon object = scene.object.outline();
    std::vector<double> out;
    for (const auto& r : taps) {
        auto contact = model.contactAt(object, r.pose);
        const auto d = contact.depthReaching(scene.tap.contactThreshold, scene.strokeLimitDepth());
        out.push_back(d ? *d : NAN);
    }
    return out;
}

StopLag stopLagOf(const std::vector<TapRecord>& taps, const std::vector<double>& crossing,
                  const SceneSpec& scene) {
    const double limit = scene.strokeLimitDepth();
    std::vector<double> lags;
    for (std::size_t i = 0; i < taps.size() && i < crossing.size(); ++i) {
        const TapRecord& r = taps[i];
        if (r.ending != TapEnding::ContactReflex || !(r.stopDepth_mm > 0.0) ||
            r.stopDepth_mm >= limit - 1e-6 || !std::isfinite(crossing[i]))
            continue;
        lags.push_back((r.stopDepth_mm - crossing[i]) / scene.tap.descentSpeed_mm_s);
    }
    StopLag lag;
    lag.taps = static_cast<int>(lags.size());
    if (lags.size() < 2) return lag;
    lag.mean = meanOf(lags);
    double ss = 0.0;
    for (double l : lags) ss += (l - lag.mean) * (l - lag.mean);
    lag.se =
        std::sqrt(ss / static_cast<double>(lags.size() - 1) / static_cast<double>(lags.size()));
    return lag;
}

Memory fitMemory(const SceneSpec& scene, const std::shared_ptr<const FingertipContactModel>& model,
                 const std::vector<TapRecord>& at, const Tail& target,
                 const std::vector<char>& skip, Memory start, int rounds, int sims,
                 std::uint64_t seed) {
    Memory m = start;
    for (int round = 0; round < rounds; ++round) {
        Tail sim;
        for (int r = 0; r < sims; ++r) {
            const Tail one = tailOf(simulateAt(withMemory(scene, m.fraction, m.tau), model, at,
                                               seed + 131 * static_cast<std::uint64_t>(r)),
                                    skip, scene.tap.contactThreshold);
            sim.early += one.early / sims;
            sim.late += one.late / sims;
        }
        if (sim.early > 0 && target.early > 0)
            m.fraction = std::clamp(m.fraction * target.early / sim.early, 1e-3, 1.0);
        if (target.early > target.late && target.late > 0 && sim.early > sim.late && sim.late > 0)
            m.tau = std::clamp(
                m.tau * std::log(sim.early / sim.late) / std::log(target.early / target.late), 0.01,
                60.0);
    }
    return m;
}

SceneSpec readLatency(const SceneSpec& given,
                      const std::shared_ptr<const FingertipContactModel>& model,
                      const std::vector<TapRecord>& recorded, const SceneFitSettings& settings,
                      double z, SceneFit& fit) {
    // The reflex's latency first, from the stroke's own travel: every simulation below then
    // presses as deep as the recorded taps did. The lag the model shows at a latency differs from
    // it by what the pose effects do to the crossing, so it is corrected by simulation (two
    // rounds of kLagSimulations recordings at the recorded poses; the mean's error adds theirs).
    const std::vector<double> crossing = crossingsOf(given, *model, recorded);
    const StopLag lag = stopLagOf(recorded, crossing, given);
    SceneSpec base = given;
    if (lag.taps >= kLagTaps) {
        double latency = std::clamp(lag.mean, 0.0, kMaxLatency_s);
        std::vector<double> simulated;
        for (int round = 0; round < 2; ++round) {
            simulated.clear();
            for (int r = 0; r < kLagSimulations; ++r)
                simulated.push_back(
                    stopLagOf(simulateAt(withLatency(given, latency), model, recorded,
                                         settings.seed + 90000 + static_cast<std::uint64_t>(r)),
                              crossing, given)
                        .mean);
            const double shown = meanOf(simulated);
            latency = std::clamp(latency + lag.mean - shown, 0.0, kMaxLatency_s);
        }
        const double spread = sd(simulated);
        const double se = std::sqrt(lag.se * lag.se + spread * spread / kLagSimulations);
        const double stat = se > 0 ? latency / se : (latency > 0 ? 1e9 : 0.0);
        const bool listed = stat > z;
        fit.choices.push_back(
            {"contact_latency", listed,
             "the mean over the " + std::to_string(lag.taps) +
                 " taps the reflex ended of the recorded stop depth less where the model at the "
                 "tap's pose reaches the threshold, over the descent speed (corrected by "
                 "simulation), over its standard error, against the one-sided normal quantile at "
                 "the level",
             stat, z, true});
        if (listed)
            fit.parameters.push_back({"contact_latency", "latency_s", latency, se,
                                      latency - 1.96 * se, latency + 1.96 * se});
        base = withLatency(given, listed ? latency : 0.0);
    } else if (given.lists("contact_latency")) {
        fit.choices.push_back({"contact_latency", true,
                               "the recording holds stop depths for " + std::to_string(lag.taps) +
                                   " taps the reflex ended (" + std::to_string(kLagTaps) +
                                   " are needed to read the latency; recordings written before "
                                   "stop depths were kept hold none): kept as the base scene "
                                   "lists it",
                               0.0, 0.0, false});
    }

    return base;
}

}  // namespace activetouch::scenefit
