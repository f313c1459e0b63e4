// The taps' holds: each pressed reading against the model at the depth it held, and the gains they
// give.
#include "devices/simulated/fit/FitHolds.h"

namespace activetouch::scenefit {

std::optional<Press> pressOf(const Tap& tap, const std::vector<char>& skip,
                             double contactThreshold) {
    Press p;
    const int T = tap.sampleCount();
    p.total = frameTotals(tap, skip);
    const auto extremes = std::minmax_element(p.total.begin(), p.total.end());
    p.lowest = *extremes.first;
    const double range = *extremes.second - p.lowest;
    if (range < 0.5 * contactThreshold) return std::nullopt;
    p.level = pressLevel(p.total, p.lowest, *extremes.second);
    p.first = -1;
    for (int t = 0; t < T; ++t)
        if (p.inHold(t)) {
            if (p.first < 0) p.first = t;
            p.last = t;
        }
    for (int t = 0; t < p.first; ++t)
        if (p.total[static_cast<std::size_t>(t)] <= p.lowest + 0.03 * range) p.quiet.push_back(t);
    if (p.first < 0 || p.quiet.size() < 2) return std::nullopt;
    return p;
}

std::optional<std::vector<double>> holdReadingOf(const Tap& tap, const std::vector<char>& skip,
                                                 double contactThreshold, double maxCounts) {
    const int K = tap.taxels;
    const auto press = pressOf(tap, skip, contactThreshold);
    if (!press) return std::nullopt;
    std::vector<double> reading(static_cast<std::size_t>(K), NAN);
    for (int k = 0; k < K; ++k) {
        if (skip[static_cast<std::size_t>(k)]) continue;
        std::vector<double> quiet;
        for (int t : press->quiet) quiet.push_back(tap.at(t, k));
        const double baseline = stats::medianOr(std::move(quiet), std::nan(""));
        std::vector<double> v;
        bool saturated = false;
        for (int t = press->first; t <= press->last; ++t)
            if (press->inHold(t)) {
                v.push_back(tap.at(t, k) - baseline);
                saturated = saturated || tap.at(t, k) >= maxCounts;
            }
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        if (!saturated) reading[static_cast<std::size_t>(k)] = v[v.size() / 2];
    }
    return reading;
}

std::vector<Hold> holdsOf(const SceneSpec& base, const FingertipContactModel& model,
                          const std::vector<TapRecord>& recorded, const std::vector<char>& skip,
                          double maxCounts, bool coupled) {
    const HoldModel grid(base, model, coupled);
    std::vector<Hold> holds;
    for (const auto& r : recorded) {
        auto reading = holdReadingOf(r.tap, skip, base.tap.contactThreshold, maxCounts);
        if (!reading) continue;
        holds.push_back({std::move(*reading), grid.at(r.pose)});
    }
    return holds;
}

std::vector<int> everyIndex(std::size_t count) {
    std::vector<int> all(count);
    std::iota(all.begin(), all.end(), 0);
    return all;
}

void resampleRuns(RandomStream& rng, std::size_t count, std::vector<int>& pick) {
    const std::size_t block = 10;
    pick.resize(count);
    for (std::size_t at = 0; at < count; at += block) {
        const auto start = std::min(
            static_cast<std::size_t>(rng.uniform() * static_cast<double>(count)), count - 1);
        for (std::size_t j = at; j < std::min(at + block, count); ++j)
            pick[j] = static_cast<int>((start + j - at) % count);
    }
}

DepthFit fitDepth(const std::vector<double>& reading, const std::vector<double>& modelAtDepths,
                  const std::vector<double>& gain, const std::vector<double>& offset) {
    const std::size_t KK = reading.size();
    DepthFit f;
    f.depths = modelAtDepths.size() / KK;
    std::vector<double> e(f.depths, 0.0);
    for (std::size_t d = 0; d < f.depths; ++d) {
        const double* p = modelAtDepths.data() + d * KK;
        for (std::size_t k = 0; k < KK; ++k) {
            const double r = reading[k];
            if (!std::isfinite(r)) continue;
            const double x = r - offset[k] - gain[k] * p[k];
            e[d] += x * x;
        }
        if (e[d] < e[f.best]) f.best = d;
    }
    f.error = e[f.best];
    if (f.best > 0 && f.best + 1 < f.depths) {
        const double curve = e[f.best - 1] - 2.0 * e[f.best] + e[f.best + 1];
        if (curve > 0) {
            f.shift = std::clamp(0.5 * (e[f.best - 1] - e[f.best + 1]) / curve, -0.5, 0.5);
            f.error -= 0.5 * curve * f.shift * f.shift;
        }
    }
    return f;
}

std::vector<double> holdLogGains(const std::vector<Hold>& holds, const std::vector<int>& which,
                                 int K) {
    const auto KK = static_cast<std::size_t>(K);
    std::vector<double> gain(KK, 1.0), offset(KK, 0.0), logGain(KK, NAN);
    std::vector<double> model(which.size() * KK);
    for (int round = 0; round < 4; ++round) {
        for (std::size_t n = 0; n < which.size(); ++n) {
            const Hold& h = holds[static_cast<std::size_t>(which[n])];
            const DepthFit f = fitDepth(h.reading, h.modelAtDepths, gain, offset);
            for (std::size_t k = 0; k < KK; ++k) model[n * KK + k] = f.at(h.modelAtDepths, KK, k);
        }
        double meanLog = 0.0;
        int read = 0;
        for (std::size_t k = 0; k < KK; ++k) {
            LineFit line;
            for (std::size_t i = 0; i < which.size(); ++i) {
                const double r = holds[static_cast<std::size_t>(which[i])].reading[k];
                const double p = model[i * KK + k];
                if (std::isfinite(r) && p > kPressed) line.add(p, r);
            }
            const double g = line.gain();
            logGain[k] = g > 0 ? std::log(g) : NAN;
            offset[k] = g > 0 ? line.offset(g) : 0.0;
            if (std::isfinite(logGain[k])) {
                meanLog += logGain[k];
                ++read;
            }
        }
        if (read == 0) return logGain;
        meanLog /= read;
        for (std::size_t k = 0; k < KK; ++k) {
            double& l = logGain[k];
            if (std::isfinite(l)) l -= meanLog;
            gain[k] = std::isfinite(l) ? std::exp(l) : 1.0;
            offset[k] = std::isfinite(l) ? offset[k] : 0.0;
        }
    }
    return logGain;
}

HoldGains holdGains(const std::vector<Hold>& holds, int K, int replicates, std::uint64_t seed) {
    HoldGains g;
    g.taps = static_cast<int>(holds.size());
    g.se.assign(static_cast<std::size_t>(K), 0.0);
    if (holds.size() < 10) {
        g.logGain.assign(static_cast<std::size_t>(K), NAN);
        return g;
    }
    const std::vector<int> all = everyIndex(holds.size());
    g.logGain = holdLogGains(holds, all, K);
    std::vector<std::vector<double>> reps(static_cast<std::size_t>(K));
    RandomStream rng(seed);
    std::vector<int> pick;
    for (int b = 0; b < replicates; ++b) {
        resampleRuns(rng, holds.size(), pick);
        const auto l = holdLogGains(holds, pick, K);
        for (int k = 0; k < K; ++k)
            if (std::isfinite(l[static_cast<std::size_t>(k)]))
                reps[static_cast<std::size_t>(k)].push_back(l[static_cast<std::size_t>(k)]);
    }
    for (int k = 0; k < K; ++k) {
        const std::size_t kk = static_cast<std::size_t>(k);
        // A taxel read in most replicates; one pressed in too few holds is left out.
        if (!std::isfinite(g.logGain[kk]) ||
            reps[kk].size() < static_cast<std::size_t>(0.9 * replicates))
            continue;
        g.se[kk] = sd(reps[kk]);
        g.df += g.se[kk] > 0 ? 1 : 0;
    }
    g.q = cochranQ(g.logGain, g.se);
    return g;
}

}  // namespace activetouch::scenefit
