// Blinking taxels: readings that drop deep for a sample or two, and how often.
#include "devices/simulated/fit/FitParts.h"

namespace activetouch::scenefit {

namespace {

/// Counts, per taxel, the deep samples and the low ones among them (a blink), the spells of
/// blinks and their readings; a frame where most deep taxels read low at once is a lost frame,
/// not a blink, and counts for none. `deep` and `low` are [t * K + k].
void countBlinks(BlinkStats& b, const Tap& tap, int K, const std::vector<char>& deep,
                 const std::vector<char>& low) {
    const int T = tap.sampleCount();
    for (int t = 0; t < T; ++t) {
        int deepHere = 0, lowHere = 0;
        for (int k = 0; k < K; ++k) {
            deepHere += deep[static_cast<std::size_t>(t * K + k)];
            lowHere += low[static_cast<std::size_t>(t * K + k)];
        }
        const bool lostFrame = deepHere >= 2 && 2 * lowHere > deepHere;
        for (int k = 0; k < K; ++k) {
            const std::size_t at = static_cast<std::size_t>(t * K + k);
            if (!deep[at] || lostFrame) continue;
            ++b.deep[static_cast<std::size_t>(k)];
            if (low[at]) {
                ++b.low[static_cast<std::size_t>(k)];
                b.lowReadings.push_back(tap.at(t, k));
                ++b.spellSamples;
                const bool continues = t > 0 &&
                                       low[static_cast<std::size_t>((t - 1) * K + k)] &&
                                       deep[static_cast<std::size_t>((t - 1) * K + k)];
                if (!continues) ++b.spells;
            }
        }
    }
}

}  // namespace

BlinkStats blinksOf(const std::vector<TapRecord>& taps, const std::vector<TapRecord>& ideal,
                    const std::vector<char>& skip, const std::vector<int>& only) {
    const int K = static_cast<int>(skip.size());
    BlinkStats b;
    b.low.assign(static_cast<std::size_t>(K), 0);
    b.deep.assign(static_cast<std::size_t>(K), 0);
    std::vector<char> asked(static_cast<std::size_t>(K), only.empty() ? 1 : 0);
    for (int k : only) asked[static_cast<std::size_t>(k)] = 1;
    for (std::size_t i = 0; i < taps.size() && i < ideal.size(); ++i) {
        const Tap& tap = taps[i].tap;
        const Tap& model = ideal[i].tap;
        const int T = tap.sampleCount();
        // deep[t * K + k], low[t * K + k]
        std::vector<char> deep(static_cast<std::size_t>(T * K), 0), low(deep.size(), 0);
        const std::vector<double> total = frameTotals(tap, skip);
        for (int k = 0; k < K; ++k) {
            if (skip[static_cast<std::size_t>(k)] || !asked[static_cast<std::size_t>(k)]) continue;
            // The recorded press, read from the other taxels (a blink of this one leaves them
            // be): frames where their total lies over four fifths of its level in the hold.
            // Where the stroke runs on another schedule than the model's, the model's press
            // alone would take the descent or the release for a blink.
            std::vector<double> others(static_cast<std::size_t>(T));
            for (int t = 0; t < T; ++t)
                others[static_cast<std::size_t>(t)] =
                    total[static_cast<std::size_t>(t)] - tap.at(t, k);
            const auto spread = std::minmax_element(others.begin(), others.end());
            const double* least = &*spread.first;
            const double level = pressLevel(others, *least, *spread.second);
            std::vector<double> readings;
            for (int t = kMargin; t + kMargin < T; ++t) {
                bool inside =
                    others[static_cast<std::size_t>(t)] >= *least + 0.8 * (level - *least);
                for (int u = t - kMargin; u <= t + kMargin && inside; ++u)
                    inside = model.at(u, k) > kBlinkDeep;
                if (!inside) continue;
                deep[static_cast<std::size_t>(t * K + k)] = 1;
                readings.push_back(tap.at(t, k));
            }
            if (readings.size() < 5) {
                for (int t = 0; t < T; ++t) deep[static_cast<std::size_t>(t * K + k)] = 0;
                continue;
            }
            std::nth_element(readings.begin(),
                             readings.begin() + static_cast<long>(readings.size() / 2),
                             readings.end());
            const double median = readings[readings.size() / 2];
            for (int t = 0; t < T; ++t) {
                const std::size_t at = static_cast<std::size_t>(t * K + k);
                if (!deep[at]) continue;
                if (!(median > kPressed)) {
                    deep[at] = 0;  // a press this taxel does not show: nothing to read
                    continue;
                }
                low[at] = tap.at(t, k) < 0.25 * median;
            }
        }
        countBlinks(b, tap, K, deep, low);
    }
    return b;
}

Blinking readBlinking(const SceneSpec& base,
                      const std::shared_ptr<const FingertipContactModel>& model,
                      const std::vector<TapRecord>& recorded, const std::vector<TapRecord>& ideal,
                      const std::vector<char>& skip, double period, std::uint64_t seed,
                      const std::vector<int>& taxels) {
    Blinking out;
    out.taxels = taxels;  // a replicate: the taxels found in the recording
    if (taxels.empty()) {
        const BlinkStats all = blinksOf(recorded, ideal, skip, {});
        for (std::size_t k = 0; k < all.low.size(); ++k) {
            out.mostLow = std::max(out.mostLow, all.low[k]);
            if (all.low[k] >= kBlinkReadings) out.taxels.push_back(static_cast<int>(k));
        }
    }
    if (out.taxels.empty()) return out;
    out.listed = true;
    const BlinkStats target = blinksOf(recorded, ideal, skip, out.taxels);
    std::vector<double> lows = target.lowReadings;
    if (!lows.empty()) {
        std::nth_element(lows.begin(), lows.begin() + static_cast<long>(lows.size() / 2),
                         lows.end());
        out.reading = std::max(0.0, std::round(lows[lows.size() / 2]));
    }
    out.offFraction = std::clamp(target.offFraction(), 1e-3, 0.95);
    out.meanOff_s = std::clamp(target.meanSpell() * period, 0.001, 60.0);
    SceneSpec scene = base;
    std::vector<EffectSpec> kept;
    for (const auto& e : base.effects)
        if (e.name != "intermittent_taxel") kept.push_back(e);
    for (int round = 0; round < 4; ++round) {
        EffectSpec e;
        e.name = "intermittent_taxel";
        e.place = "/effects/" + std::to_string(kept.size());
        e.parameters = Json{{"taxels", out.taxels},
                            {"off_fraction", out.offFraction},
                            {"mean_off_s", out.meanOff_s},
                            {"reading_counts", out.reading}};
        scene.effects = kept;
        scene.effects.push_back(e);
        double share = 0.0, spell = 0.0;
        for (int r = 0; r < 2; ++r) {
            const BlinkStats sim = blinksOf(
                simulateAt(scene, model, recorded, seed + 7919 * static_cast<std::uint64_t>(r)),
                ideal, skip, out.taxels);
            share += 0.5 * sim.offFraction();
            spell += 0.5 * sim.meanSpell();
        }
        if (share > 0)
            out.offFraction =
                std::clamp(out.offFraction * target.offFraction() / share, 1e-3, 0.95);
        if (spell > 0)
            out.meanOff_s = std::clamp(out.meanOff_s * target.meanSpell() / spell, 0.001, 60.0);
    }
    return out;
}

}  // namespace activetouch::scenefit
