#include "devices/simulated/SceneFit.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>

#include "core/stats/Distributions.h"
#include "core/common/InputError.h"
#include "core/common/NumberText.h"
#include "core/run/ExperimentRun.h"
#include "devices/simulated/SimulatedWorld.h"

namespace activetouch {
namespace {

/// The effects this fit estimates from taps; every other effect is kept as the base lists it.
const char* const kEstimated[] = {"taxel_noise", "baseline_drift",   "taxel_gain",
                                  "dead_taxel",  "adc_quantisation", "intermittent_taxel"};

bool estimatedHere(const std::string& name) {
    for (const char* e : kEstimated)
        if (name == e) return true;
    return false;
}

/// What the fit varies.
struct Theta {
    double sigma = 0.0;  ///< taxel_noise sigma_counts
    double rate = 0.0;   ///< baseline_drift rate_counts_per_sqrt_s
    std::vector<double> gains;
};

/// The statistics both recorded and simulated taps are read through.
struct Moments {
    double within = 0.0;  ///< mean within-(tap, taxel) variance of samples over nothing
    double wander = 0.0;  ///< variance over taps of the (tap, taxel) means over nothing, less noise
    std::vector<double> pressure;  ///< per taxel, the summed readings of samples in contact
    long nothing = 0;
};

/// Which samples of each tap touch nothing and which touch, from the noise-free model.
struct Masks {
    std::vector<std::vector<char>> nothing;  ///< [tap][sample]
    /// [tap][sample * K + taxel]: the model presses the taxel over kPressed counts in the tap
    std::vector<std::vector<char>> pressed;
    /// A sample the model takes over nothing is read as such only where its frame's total lies
    /// within this many counts above the tap's quiet level (see quietFrames()).
    double quietMargin = 0.0;
};

/// Each frame's total over the live taxels of `tap`.
std::vector<double> frameTotals(const Tap& tap, const std::vector<char>& skip) {
    std::vector<double> total(static_cast<std::size_t>(tap.sampleCount()), 0.0);
    for (int t = 0; t < tap.sampleCount(); ++t)
        for (int k = 0; k < tap.taxels; ++k)
            if (!skip[static_cast<std::size_t>(k)])
                total[static_cast<std::size_t>(t)] += tap.at(t, k);
    return total;
}

/// The level of a press in frame totals `total` whose least and most are `lowest` and `highest`:
/// the median of the totals above half the range, most of which are the hold's (a pad with
/// memory reads above it for a frame after release).
double pressLevel(const std::vector<double>& total, double lowest, double highest) {
    std::vector<double> upper;
    for (double v : total)
        if (v >= lowest + 0.5 * (highest - lowest)) upper.push_back(v);
    std::nth_element(upper.begin(), upper.begin() + static_cast<long>(upper.size() / 2),
                     upper.end());
    return upper[upper.size() / 2];
}

/// Per frame of `tap`, whether its total over the live taxels lies within `margin` counts above
/// the tap's quiet level (the tenth percentile of its frames' totals). A stroke on another
/// schedule than the model's (a real tapper's, or one the host held up) presses where the model
/// does not; this keeps such frames out of what is read as over nothing, alike in recorded and
/// simulated taps, and noise alone does not reach it.
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
constexpr double kPressed = 20.0;
/// The widest coupling the crosstalk effect takes, either way (read values may fall below zero).
constexpr double kMaxCoupling = 0.5;
/// The crosstalk's neighbourhood where the base scene gives none (the effect's default), mm.
constexpr double kDefaultCouplingRadius_mm = 4.5;
/// A converter's range shows as at least this many readings at the highest value, and this many
/// times as many as one count below it.
constexpr long kPileReadings = 20;
constexpr long kPileRatio = 4;
constexpr int kMargin = 4;

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

/// The scene with the fitted effects in place of the base's own of those names.
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

/// Taps simulated with `scene` at the poses of `at`; with `strokes`, each stopping where its
/// recorded namesake did where that was recorded (a tap the reflex ended, with its stop depth).
std::vector<TapRecord> simulateAt(const SceneSpec& scene,
                                  const std::shared_ptr<const FingertipContactModel>& model,
                                  const std::vector<TapRecord>& at, std::uint64_t seed,
                                  bool strokes = false) {
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

struct FitContext {
    const SceneSpec& base;
    std::shared_ptr<const FingertipContactModel> model;
    const Masks& masks;
    const std::vector<TapRecord>& poses;
    bool quantised;
    double maxCounts;
    std::vector<int> dead;
    double deadReading;
    const EffectSpec* driftTemplate;
    const EffectSpec* blink;
    std::vector<char> skip;
    int iterations;
    int simulations;
};

/// The parameters at which simulated taps show `target`'s moments.
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

/// Readings deep inside a press (the model presses the taxel over kBlinkDeep counts from
/// kMargin samples before to kMargin after) that fall under a quarter of the taxel's median over
/// that stretch of the tap, where that median is over kPressed; a frame in which most of the
/// pressed taxels fall together is a lost frame, not a blink, and is left out.
constexpr double kBlinkDeep = 30.0;
/// A taxel is taken to blink from this many such readings: noise on a live taxel gives none
/// (a reading a quarter of a median over 20 counts lies over ten noise deviations below it).
constexpr long kBlinkReadings = 5;

struct BlinkStats {
    std::vector<long> low, deep;        ///< per taxel
    long spells = 0, spellSamples = 0;  ///< runs of low readings over the taxels asked about
    std::vector<double> lowReadings;
    double offFraction() const {
        long l = 0, d = 0;
        for (std::size_t k = 0; k < low.size(); ++k) {
            l += low[k];
            d += deep[k];
        }
        return d > 0 ? static_cast<double>(l) / static_cast<double>(d) : 0.0;
    }
    double meanSpell() const {
        return spells > 0 ? static_cast<double>(spellSamples) / static_cast<double>(spells) : 0.0;
    }
};

/// The blink statistics of `taps` against the noise-free `ideal` taps at the same poses, over
/// `only` (every live taxel when empty).
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
    return b;
}

struct Blinking {
    bool listed = false;
    std::vector<int> taxels;
    long mostLow = 0;
    double offFraction = 0.0, meanOff_s = 0.0, reading = 0.0;
};

/// Which taxels blink, and how: the share of time off and the mean off spell, at which taps
/// simulated at the recorded poses show the recorded share of low readings and mean run of
/// them (a few rounds of the same moment matching as the other effects). One share and one
/// spell for every blinking taxel, as the effect takes them. `taxels`, where given, are the ones
/// read.
Blinking readBlinking(const SceneSpec& base,
                      const std::shared_ptr<const FingertipContactModel>& model,
                      const std::vector<TapRecord>& recorded, const std::vector<TapRecord>& ideal,
                      const std::vector<char>& skip, double period, std::uint64_t seed,
                      const std::vector<int>& taxels = {}) {
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

double ksDistance(std::vector<double> a, std::vector<double> b) {
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    std::size_t i = 0, j = 0;
    double d = 0.0;
    while (i < a.size() && j < b.size()) {
        const double x = std::min(a[i], b[j]);
        while (i < a.size() && a[i] <= x) ++i;
        while (j < b.size() && b[j] <= x) ++j;
        d = std::max(
            d, std::abs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
    }
    return d;
}

double wasserstein(std::vector<double> a, std::vector<double> b) {
    // Between two empirical distributions: the mean gap of their quantiles.
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    const std::size_t n = 1000;
    double sum = 0.0;
    for (std::size_t q = 0; q < n; ++q) {
        const double p = (q + 0.5) / n;
        sum += std::abs(a[static_cast<std::size_t>(p * a.size())] -
                        b[static_cast<std::size_t>(p * b.size())]);
    }
    return sum / n;
}

std::vector<double> readings(const std::vector<TapRecord>& taps, int k) {
    std::vector<double> v;
    for (const auto& r : taps)
        for (int t = 0; t < r.tap.sampleCount(); ++t) v.push_back(r.tap.at(t, k));
    return v;
}

/// The mean of `v` (non-empty).
double meanOf(const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double sd(const std::vector<double>& v) {
    if (v.size() < 2) return 0.0;
    const double m = meanOf(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / (v.size() - 1));
}

/// How far `value` lies above the mean of `nulls` (recordings simulated without an effect), in
/// their standard deviations; 1e9 above a mean they do not spread about, 0 at or below it.
double zAbove(double value, const std::vector<double>& nulls) {
    const double spread = sd(nulls);
    const double expected = meanOf(nulls);
    return spread > 0 ? (value - expected) / spread : (value > expected ? 1e9 : 0.0);
}

/// Cochran's Q of `logs` about their inverse-variance weighted mean, over the entries whose
/// standard error `se` is positive (so that one read loosely moves the centre little); 0 for
/// none.
double cochranQ(const std::vector<double>& logs, const std::vector<double>& se) {
    double weightSum = 0.0, weighted = 0.0;
    for (std::size_t k = 0; k < logs.size(); ++k)
        if (se[k] > 0) {
            weightSum += 1.0 / (se[k] * se[k]);
            weighted += logs[k] / (se[k] * se[k]);
        }
    if (weightSum <= 0) return 0.0;
    const double centre = weighted / weightSum;
    double q = 0.0;
    for (std::size_t k = 0; k < logs.size(); ++k)
        if (se[k] > 0) {
            const double d = (logs[k] - centre) / se[k];
            q += d * d;
        }
    return q;
}

/// The taxels' sensitivities relative to one another, read from the holds alone so that a stroke
/// on another schedule or to another depth than the scene's reads the same (see fitScene()).
struct HoldGains {
    std::vector<double> logGain, se;  ///< per taxel, about their plain mean; se 0 = not read
    int taps = 0;                     ///< touching taps whose hold was read
    double q = 0.0;                   ///< Cochran's Q of the log gains
    int df = 0;                       ///< taxels read
};

constexpr double kHoldShare = 0.95;

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

/// The median of `v` (the mean of the middle two for an even count).
double medianOf(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]);
}

/// A touching tap's hold: each taxel's median over the frames of the hold, less its baseline
/// before contact, and the model's pressures at the tap's pose over a grid of depths to the
/// stroke's limit.
struct Hold {
    std::vector<double> reading;        ///< per taxel; NaN where unusable (saturated)
    std::vector<double> modelAtDepths;  ///< [depth][taxel]
};
constexpr int kHoldDepths = 120;

/// The hold's readings of `tap` (see Hold), or nothing for a tap without a press.
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
        const double baseline = medianOf(std::move(quiet));
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
                          double maxCounts, bool coupled = true) {
    const HoldModel grid(base, model, coupled);
    std::vector<Hold> holds;
    for (const auto& r : recorded) {
        auto reading = holdReadingOf(r.tap, skip, base.tap.contactThreshold, maxCounts);
        if (!reading) continue;
        holds.push_back({std::move(*reading), grid.at(r.pose)});
    }
    return holds;
}

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
std::vector<int> everyIndex(std::size_t count) {
    std::vector<int> all(count);
    std::iota(all.begin(), all.end(), 0);
    return all;
}

/// Runs of ten consecutive entries of `count`, each starting where `rng` says, into `pick` (as
/// many as `count`): a resampling that keeps neighbours together (a drifting baseline ties
/// consecutive taps).
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

/// The grid the hold offsets are read on: this many steps each way of kOffsetStep_mm, then
/// kOffsetSteps each way of a fifth of that about the best.
constexpr int kOffsetSteps = 6;
constexpr double kOffsetStep_mm = 0.05;

/// How far each tap lies off its commanded pose across the outline, as its hold shows it: the
/// shift along the outward normal of the outline's nearest edge at which the noise-free model,
/// its depth fitted alongside, fits the hold's readings best (the parabola through the best of a
/// fine grid about the best of a coarse one); NaN for a tap without a hold, one the reflex did not
/// end short of the stroke's limit, and one whose hold the coarse grid does not bracket.
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

/// A tap whose offset varies less than this (mm squared) over recordings at its pose is not read:
/// its hold does not place it (the fit sits at the grid's end, or the model does not change).
constexpr double kLeastOffsetVariance = 1e-8;
/// The largest stage error the effect takes, mm.
constexpr double kMaxStageSigma_mm = 2.0;

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
                          std::size_t leaveOut = static_cast<std::size_t>(-1)) {
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

/// Log gains (about their plain mean) from the holds picked by `which`: alternately each hold's
/// depth (the grid point, refined by a parabola, that fits its readings best with the taxels'
/// lines so far) and each taxel's line, reading = offset + gain x model, by least squares over
/// the holds that press it over kPressed counts at their depth. The offset takes what a baseline
/// under zero hides: a skin that clamps its readings at zero reads nothing over nothing whether
/// its baseline lies a little below or at zero, but a press shows the difference. NaN for a
/// taxel fewer than five holds press so.
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

/// The pairs (reader, neighbour) the crosstalk effect couples at `radius_mm`, as it takes them.
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

/// The crosstalk's coupling as the holds picked by `which` show it (holds of the bare contact):
/// each taxel reads offset + gain x (its own pressure + c x its neighbours'), alternately each
/// hold's depth (fitDepth() on those pressures), each taxel's line by least squares over the
/// holds that press it or its neighbours over kPressed counts at their depth, and the common c,
/// four rounds from c = 0.
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

/// The coupling with its standard error from resampling runs of ten consecutive holds.
struct Coupling {
    double value = 0.0, se = 0.0;
    int holds = 0;
};
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

/// The hold gains with their errors from resampling the touching taps, and Cochran's Q of
/// their logs about the inverse-variance weighted mean.
/// The pad's memory as the taps show it: after each touching tap's press falls, what its total
/// still reads over its baseline before contact, as a share of the press's level, early (the
/// first three frames after the fall) and late (the seventh to tenth), averaged over the taps
/// whose window holds ten frames after the fall. The fall ends at the first frame after the
/// hold that lies below half the level and drops by less than a twentieth of it from the frame
/// before. Read from the taps alone, so that a stroke on another schedule reads alike.
struct Tail {
    double early = 0.0, late = 0.0;
    int taps = 0;
};
constexpr int kTailFrames = 10;

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
        const double base = medianOf(std::move(quiet));
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

/// `scene` with effect `name` at `parameters` in place of its own, or without it where
/// `parameters` is null.
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

/// `scene` with the pad's memory at (fraction, time constant), or without it at fraction 0.
SceneSpec withMemory(const SceneSpec& scene, double fraction, double tau) {
    return withEffect(
        scene, "viscoelastic_memory",
        fraction > 0 ? Json{{"fraction", fraction}, {"time_constant_s", tau}} : Json());
}

/// `scene` with the reflex's latency at `latency_s`, or without one at 0.
SceneSpec withLatency(const SceneSpec& scene, double latency_s) {
    return withEffect(scene, "contact_latency",
                      latency_s > 0 ? Json{{"latency_s", latency_s}} : Json());
}

/// A latency is read from this many taps the reflex ended with their stop depths recorded.
constexpr int kLagTaps = 10;
/// Recordings simulated per round of the latency's correction.
constexpr int kLagSimulations = 10;
/// The longest latency the effect takes.
constexpr double kMaxLatency_s = 0.5;

/// Where the noise-free model at each tap's pose reaches the reflex's threshold within the
/// stroke, mm below the object's top (NaN where it does not).
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

/// The reflex's lag as the recorded stop depths show it, over the taps the reflex ended with a
/// stop depth recorded short of the stroke's limit where the model at the pose reaches the
/// threshold (`crossing`): each tap's stop depth less that depth, over the descent speed. Its
/// mean, the mean's standard error, and the taps read. The stroke's own travel says it, not the
/// skin: a skin less sensitive throughout does not move it.
struct StopLag {
    double mean = 0.0, se = 0.0;
    int taps = 0;
};
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

struct Memory {
    double fraction = 0.0, tau = 0.0;
};

/// The memory at which taps simulated at the recorded poses with `scene` show the recorded
/// tail: the fraction scaled by the early shares' ratio, the time constant by the ratio of
/// their early-to-late logs, over `rounds` rounds from `start`, each round's tail the mean of
/// `sims` simulations with the same seeds every round (so that one simulation's noise does not
/// move the estimate from round to round).
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

/// The reflex's latency, read first, from the stroke's own travel (see the comment inside): its
/// choice and estimate into `fit`, and the scene every later simulation takes (`given` with the
/// latency read, or as it is where the recording holds too few stop depths).
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

/// Crosstalk (see the comment inside): its choice and estimate into `fit`, and `base` with the
/// coupling read (or without one).
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

/// The stage's error (see the comment inside), against `fit.fitted` as fitted so far: its
/// choice and estimate into `fit`, and the error read, where the taps show one.
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
    std::optional<double> stageSigma;
    {
        const HoldModel grid(base, *model);
        const double threshold = base.tap.contactThreshold;
        const double limit = base.strokeLimitDepth();
        auto offsetsIn = [&](const SceneSpec& scene, std::uint64_t seed) {
            return holdOffsetsOf(grid, simulateAt(scene, model, recorded, seed, true), skip,
                                 threshold, maxCounts, limit);
        };
        const auto offsets = holdOffsetsOf(grid, recorded, skip, threshold, maxCounts, limit);
        // The scene as fitted: only the effects listed, at their estimates.
        const SceneSpec& fitted = fit.fitted;
        const SceneSpec exact = withEffect(fitted, "stage_error", Json());
        std::vector<std::vector<double>> nulls;
        for (int b = 0; b < std::max(settings.bootstrapReplicates, 10); ++b)
            nulls.push_back(
                offsetsIn(exact, settings.seed + 95000 + static_cast<std::uint64_t>(b)));
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
        // How small a stage error the test can see: one whose excess reaches the quantile (the
        // excess grows as the error's square over each tap's variance).
        const double precision = spread.precision;
        const double smallest = precision > 0 ? std::sqrt(z * sd(nullExcess) / precision) : NAN;
        if (listed) {
            // The excess grows as the error's square: scaled until recordings simulated at the
            // estimate show the recorded one (three rounds of three).
            double sigma = std::clamp(std::sqrt(std::max(spread.excess(), 0.0) / precision), 1e-3,
                                      kMaxStageSigma_mm);
            auto excessAt = [&](double at, int count, std::uint64_t seed) {
                std::vector<double> out;
                for (int r = 0; r < count; ++r)
                    out.push_back(offsetSpread(offsetsIn(withEffect(fitted, "stage_error",
                                                                    Json{{"sigma_mm", at}}),
                                                         seed + 7 * static_cast<std::uint64_t>(r)),
                                               nulls)
                                      .excess());
                return out;
            };
            for (int round = 0; round < 3; ++round) {
                const auto shown = excessAt(sigma, 3, settings.seed + 96000);
                const double mean = meanOf(shown);
                if (mean > 0)
                    sigma = std::clamp(sigma * std::sqrt(std::max(spread.excess(), 0.0) / mean),
                                       1e-3, kMaxStageSigma_mm);
            }
            const auto again =
                excessAt(sigma, std::max(settings.bootstrapReplicates, 5), settings.seed + 97000);
            const double mean = meanOf(again);
            std::vector<double> sigmas;
            for (double e : again) sigmas.push_back(sigma * std::sqrt(std::max(e, 0.0) / mean));
            // Every replicate is set against the same simulated recordings of an exact stage, so
            // their spread misses what those recordings' own finite number adds to the recorded
            // excess: the spread of the excess among them, through dσ = σ dE / 2E.
            const double viaNulls = mean > 0 ? sigma * sd(nullExcess) / (2.0 * mean) : 0.0;
            const double se = std::hypot(sd(sigmas), viaNulls);
            stageSigma = sigma;
            fit.choices.push_back({"stage_error", true, test, stat, z, true});
            fit.parameters.push_back(
                {"stage_error", "sigma_mm", sigma, se, sigma - 1.96 * se, sigma + 1.96 * se});
        } else {
            fit.choices.push_back(
                {"stage_error", given.lists("stage_error"),
                 test + "; under it, so " +
                     (given.lists("stage_error") ? "kept as the base scene lists it"
                                                 : std::string("not listed")) +
                     " (these taps would show a stage error of about " +
                     numberText(std::round(smallest * 1000.0) / 1000.0) + " mm and more)",
                 stat, z, false});
        }
    }
    return stageSigma;
}

}  // namespace

SceneFit fitScene(const SceneSpec& given, const std::vector<TapRecord>& recorded,
                  const SceneFitSettings& settings) {
    if (recorded.size() < 20)
        throw InputError(settings.recording, "",
                         "a fit needs at least 20 recorded taps; the recording has " +
                             std::to_string(recorded.size()));
    auto model = std::make_shared<const FingertipContactModel>(given.fingertip);
    const int K = model->taxelCount();
    for (const auto& r : recorded)
        if (r.tap.taxels != K || r.tap.sampleCount() != given.tap.samples)
            throw InputError(settings.recording, "",
                             "the recording's taps have " + std::to_string(r.tap.sampleCount()) +
                                 " samples of " + std::to_string(r.tap.taxels) +
                                 " taxels, but the scene's fingertip and tap (" +
                                 (given.source.empty() ? std::string("the experiment's scene")
                                                       : given.source + " at /tap/samples") +
                                 ") say " + std::to_string(given.tap.samples) + " of " +
                                 std::to_string(K) + "; give the scene the taps were taken with");
    SceneFit fit;
    const double z = stats::normalUpper(settings.alpha);

    // The reflex's latency first: every simulation below then presses, on average, as deep as
    // the recorded taps did.
    SceneSpec base = readLatency(given, model, recorded, settings, z, fit);

    // Samples over nothing: the noise-free model at each recorded pose touches nothing there.
    SceneSpec ideal = base;
    ideal.effects.clear();
    const std::vector<TapRecord> idealTaps = simulateAt(ideal, model, recorded, 1);
    Masks masks;
    masks.quietMargin = 0.1 * base.tap.contactThreshold;
    // Read so that a tapper whose stroke runs on another schedule than the simulated one (a real
    // rig's) is read the same: a taxel is pressed in a tap where the model presses it over
    // kPressed counts at some sample, and its pressure is the whole tap's.
    for (const auto& r : idealTaps) {
        double total = 0.0;
        std::vector<char> pressedTaxel(static_cast<std::size_t>(K), 0);
        for (int t = 0; t < r.tap.sampleCount(); ++t)
            for (int k = 0; k < K; ++k) {
                total += r.tap.at(t, k);
                if (r.tap.at(t, k) > kPressed) pressedTaxel[static_cast<std::size_t>(k)] = 1;
            }
        // Over nothing: a whole tap off the object, or the samples of the descent that end
        // kMargin samples before the model's first contact (a stroke on another schedule may
        // touch a little earlier).
        int firstContact = r.tap.sampleCount();
        for (int t = 0; t < r.tap.sampleCount() && firstContact == r.tap.sampleCount(); ++t)
            for (int k = 0; k < K; ++k)
                if (r.tap.at(t, k) > 0.0) firstContact = t;
        std::vector<char> nothing(static_cast<std::size_t>(r.tap.sampleCount()), 0);
        for (int t = 0; t < r.tap.sampleCount(); ++t)
            nothing[static_cast<std::size_t>(t)] = total == 0.0 || t < firstContact - kMargin;
        std::vector<char> pressed(r.tap.samples.size(), 0);
        for (int t = 0; t < r.tap.sampleCount(); ++t)
            for (int k = 0; k < K; ++k)
                pressed[static_cast<std::size_t>(t * K + k)] =
                    pressedTaxel[static_cast<std::size_t>(k)];
        masks.nothing.push_back(std::move(nothing));
        masks.pressed.push_back(std::move(pressed));
    }

    fit.taps = static_cast<int>(recorded.size());
    // Dead or stuck taxels: where the model presses a taxel hard, it reads no more than over
    // nothing (under a twentieth of the median taxel's response).
    std::vector<char> skip(static_cast<std::size_t>(K), 0);
    {
        std::vector<double> response(static_cast<std::size_t>(K), 0.0);
        std::vector<std::vector<double>> all(static_cast<std::size_t>(K));
        for (int k = 0; k < K; ++k) {
            double pressed = 0.0, idle = 0.0;
            long nPressed = 0, nIdle = 0;
            for (std::size_t i = 0; i < recorded.size(); ++i)
                for (int t = 0; t < recorded[i].tap.sampleCount(); ++t) {
                    const double v = recorded[i].tap.at(t, k);
                    all[static_cast<std::size_t>(k)].push_back(v);
                    if (masks.nothing[i][static_cast<std::size_t>(t)]) {
                        idle += v;
                        ++nIdle;
                    } else if (masks.pressed[i][static_cast<std::size_t>(t * K + k)]) {
                        pressed += v;
                        ++nPressed;
                    }
                }
            response[static_cast<std::size_t>(k)] =
                nPressed >= 20 && nIdle > 0 ? pressed / nPressed - idle / nIdle : NAN;
        }
        std::vector<double> live;
        for (double r : response)
            if (std::isfinite(r)) live.push_back(r);
        std::sort(live.begin(), live.end());
        const double median = live.empty() ? 0.0 : live[live.size() / 2];
        for (int k = 0; k < K; ++k) {
            const double r = response[static_cast<std::size_t>(k)];
            if (!(std::isfinite(r) && median > 0 && r < 0.05 * median)) continue;
            fit.deadTaxels.push_back(k);
            skip[static_cast<std::size_t>(k)] = 1;
            auto& v = all[static_cast<std::size_t>(k)];
            std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
            fit.deadReading = v[v.size() / 2];  // its reading under the noise
        }
    }
    // The converter: every reading a whole count. Its range: a converter that saturates piles
    // its readings at the top of its range (every reading that would lie above it), where a
    // reading tail that does not reach it thins out to a few at its highest value.
    bool whole = true;
    double top = 0.0;
    for (const auto& r : recorded)
        for (double v : r.tap.samples) {
            whole = whole && v == std::floor(v);
            top = std::max(top, v);
        }
    long atTop = 0, belowTop = 0;
    for (const auto& r : recorded)
        for (double v : r.tap.samples) {
            atTop += v == top;
            belowTop += v < top && v >= top - 1.0;
        }
    const bool saturates = whole && atTop >= kPileReadings && atTop >= kPileRatio * belowTop;
    double maxCounts = 255.0;
    for (const auto& e : base.effects)
        if (e.name == "adc_quantisation" && e.parameters.contains("max_counts"))
            maxCounts = e.parameters["max_counts"].get<double>();
    maxCounts = saturates ? top : std::max(maxCounts, top);

    // Blinking taxels, read before the gains so that every simulation the gains are fitted to
    // blinks alike.
    const double period = 1.0 / base.tap.sampleRate_hz;
    const Blinking blinking =
        readBlinking(base, model, recorded, idealTaps, skip, period, settings.seed + 30000);
    EffectSpec blinkEffect;
    blinkEffect.name = "intermittent_taxel";
    blinkEffect.parameters = Json{{"taxels", blinking.taxels},
                                  {"off_fraction", blinking.offFraction},
                                  {"mean_off_s", blinking.meanOff_s},
                                  {"reading_counts", blinking.reading}};

    // Crosstalk, before the noise, drift and gains: a coupling left out is taken for gains.
    base = readCrosstalk(given, base, model, recorded, skip, maxCounts, settings, z, fit);

    // Into `base`, which stays as it is from here on.
    const EffectSpec* driftTemplate = nullptr;
    for (const auto& e : base.effects)
        if (e.name == "baseline_drift") driftTemplate = &e;

    const Moments target = momentsOf(recorded, masks, skip);
    fit.nothingSamples = target.nothing;
    if (target.nothing < 1000)
        throw InputError(settings.recording, "",
                         "the recording has only " + std::to_string(target.nothing) +
                             " samples over nothing (off the object, or before contact); the "
                             "noise and drift cannot be read from it");
    FitContext c{base,
                 model,
                 masks,
                 recorded,
                 whole,
                 maxCounts,
                 fit.deadTaxels,
                 fit.deadReading,
                 driftTemplate,
                 blinking.listed ? &blinkEffect : nullptr,
                 skip,
                 settings.iterations,
                 settings.simulationsPerRound};
    const Theta raw = fitMoments(c, target, settings.seed);
    const SceneSpec fittedAll = sceneWith(base, raw, whole, maxCounts, fit.deadTaxels,
                                          fit.deadReading, driftTemplate, c.blink);

    // Uncertainty: the same fit on recordings simulated with the estimate.
    std::vector<double> sigmas, rates, offFractions, offSpells;
    std::vector<std::vector<double>> logGains(static_cast<std::size_t>(K));
    for (int b = 0; b < settings.bootstrapReplicates; ++b) {
        const auto replicate = simulateAt(fittedAll, model, recorded,
                                          settings.seed + 1000 + static_cast<std::uint64_t>(b));
        // A replicate's blinks are read again, so that the gains' spread carries theirs.
        FitContext rc = c;
        Blinking again;
        EffectSpec againEffect = blinkEffect;
        if (blinking.listed) {
            again = readBlinking(base, model, replicate, idealTaps, skip, period,
                                 settings.seed + 40000 + 100 * static_cast<std::uint64_t>(b),
                                 blinking.taxels);
            againEffect.parameters["off_fraction"] = again.offFraction;
            againEffect.parameters["mean_off_s"] = again.meanOff_s;
            rc.blink = &againEffect;
        }
        const Theta th = fitMoments(rc, momentsOf(replicate, masks, skip),
                                    settings.seed + 5000 + static_cast<std::uint64_t>(b));
        sigmas.push_back(th.sigma);
        rates.push_back(th.rate);
        if (blinking.listed) {
            offFractions.push_back(again.offFraction);
            offSpells.push_back(again.meanOff_s);
        }
        for (int k = 0; k < K; ++k)
            logGains[static_cast<std::size_t>(k)].push_back(
                std::log(th.gains[static_cast<std::size_t>(k)]));
    }
    // The moment fit leans (by about 4 % of the noise on the paper's protocol): the estimate is
    // corrected by the lean the replicates show about it (the bootstrap's bias correction).
    Theta est = raw;
    if (!sigmas.empty()) {
        est.sigma = std::max(0.0, 2.0 * raw.sigma - meanOf(sigmas));
        est.rate = raw.rate > 0 ? std::max(0.0, 2.0 * raw.rate - meanOf(rates)) : 0.0;
        for (int k = 0; k < K; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            if (!skip[kk])
                est.gains[kk] = std::clamp(
                    std::exp(2.0 * std::log(raw.gains[kk]) - meanOf(logGains[kk])), 0.05, 20.0);
        }
    }
    auto parameter = [&](const std::string& effect, const std::string& name, double value,
                         double se) {
        fit.parameters.push_back({effect, name, value, se, value - 1.96 * se, value + 1.96 * se});
    };
    Theta chosen = est;
    // Noise and drift: listed when the estimate lies more than z standard errors above zero.
    auto aboveZero = [&](const char* effect, const char* name, const char* what, double value,
                         const std::vector<double>& replicates) {
        const double se = sd(replicates);
        const double stat = se > 0 ? value / se : (value > 0 ? 1e9 : 0.0);
        const bool listed = stat > z;
        fit.choices.push_back({effect, listed,
                               std::string(what) +
                                   " / its standard error against the one-sided normal quantile "
                                   "at the level",
                               stat, z, true});
        if (listed) parameter(effect, name, value, se);
        return listed;
    };
    if (!aboveZero("taxel_noise", "sigma_counts", "sigma", est.sigma, sigmas)) chosen.sigma = 0.0;
    {
        // Drift: whether the taps' means over nothing wander more than recordings simulated
        // with the fitted scene but no drift do. (A rate over its standard error would test at
        // the boundary: replicates simulated at a small rate read it back as small or as none,
        // and their spread is then no measure of how far from none it lies.)
        Theta none = est;
        none.rate = 0.0;
        const SceneSpec noDrift = sceneWith(base, none, whole, maxCounts, fit.deadTaxels,
                                            fit.deadReading, driftTemplate, c.blink);
        std::vector<double> wanders;
        for (int b = 0; b < std::max(settings.bootstrapReplicates, 10); ++b)
            wanders.push_back(
                momentsOf(simulateAt(noDrift, model, recorded,
                                     settings.seed + 70000 + static_cast<std::uint64_t>(b)),
                          masks, skip)
                    .wander);
        const double stat = zAbove(target.wander, wanders);
        const bool listed = est.rate > 0 && stat > z;
        fit.choices.push_back(
            {"baseline_drift", listed,
             "the wander of the taps' means over nothing, less its mean over " +
                 std::to_string(wanders.size()) +
                 " recordings simulated with the fitted scene without drift, over their standard "
                 "deviation, against the one-sided normal quantile at the level",
             stat, z, true});
        if (listed)
            parameter("baseline_drift", "rate_counts_per_sqrt_s", est.rate, sd(rates));
        else
            chosen.rate = 0.0;
    }
    {
        // Gains: a Wald test of the log gains' spread about their common value (chi-square with
        // one degree of freedom fewer than the live taxels). Their common level is the tapper's as
        // much as the skin's (a deeper stop presses every taxel harder), so it is reported apart.
        std::vector<double> ses(static_cast<std::size_t>(K), 0.0);
        double meanLog = 0.0, meanLogVar = 0.0;
        int df = 0;
        for (int k = 0; k < K; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            if (skip[kk]) continue;
            ses[kk] = sd(logGains[kk]);
            meanLog += std::log(est.gains[kk]);
            meanLogVar += ses[kk] * ses[kk];
            ++df;
        }
        if (df > 0) {
            meanLog /= df;
            meanLogVar /= static_cast<double>(df) * df;
        }
        // The same statistic on these gains, for the report (skipped taxels have no error).
        std::vector<double> logs(static_cast<std::size_t>(K), 0.0);
        for (int k = 0; k < K; ++k)
            logs[static_cast<std::size_t>(k)] = std::log(est.gains[static_cast<std::size_t>(k)]);
        const double wald = cochranQ(logs, ses);
        // Whether the taxels differ is read from the holds (holdGains()): the moment fit above
        // compares whole taps with the scene's stroke, so a stroke that stops deeper or on
        // another schedule would look like gains there. The values and their intervals are the
        // moment fit's.
        const HoldGains held = holdGains(holdsOf(base, *model, recorded, skip, maxCounts), K,
                                         settings.holdReplicates, settings.seed + 60000);
        fit.holdTaps = held.taps;
        fit.momentGainsQ = wald;
        for (std::size_t k = 0; k < held.logGain.size(); ++k) {
            fit.holdGains.push_back(std::exp(held.logGain[k]));
            fit.holdGainLogSe.push_back(held.se[k]);
        }
        const double threshold = held.df > 1 ? stats::chiSquareUpper(held.df - 1, settings.alpha) : 0.0;
        const bool listed = held.df > 1 && held.q > threshold;
        fit.choices.push_back(
            {"taxel_gain", listed,
             "Cochran's Q of the log gains read from the taps' holds (each hold's "
             "depth fitted to the model at its pose) about their "
             "inverse-variance weighted mean, errors from resampling the taps, "
             "against chi-square with one degree of freedom fewer than the "
             "taxels read, at the level",
             held.q, threshold, true});
        const double seCommon = std::sqrt(meanLogVar);
        fit.pressureScale = std::exp(meanLog);
        fit.pressureScaleLow = std::exp(meanLog - 1.96 * seCommon);
        fit.pressureScaleHigh = std::exp(meanLog + 1.96 * seCommon);
        fit.pressureScaleDiffers =
            seCommon > 0 ? std::abs(meanLog) / seCommon > stats::normalUpper(settings.alpha / 2)
                         : meanLog != 0.0;
        if (listed) {
            // The gains are one family: 95 % intervals that hold for every live taxel at once
            // (Bonferroni), each from its log's.
            const double zAll = stats::normalUpper(0.025 / std::max(df, 1));
            for (int k = 0; k < K; ++k) {
                const std::size_t kk = static_cast<std::size_t>(k);
                if (skip[kk]) continue;
                const double g = est.gains[kk];
                fit.parameters.push_back({"taxel_gain", "gain_" + std::to_string(k), g, g * ses[kk],
                                          g * std::exp(-zAll * ses[kk]),
                                          g * std::exp(zAll * ses[kk])});
            }
        } else {
            std::fill(chosen.gains.begin(), chosen.gains.end(), 1.0);
        }
    }
    // The pad's memory: listed where the taps' early tail after a press lies above what
    // recordings simulated with the fitted scene without memory show (the drift test's form),
    // then fitted by simulation, with standard errors from recordings simulated at the estimate.
    Memory memory;
    bool memoryListed = false;
    {
        const Tail target = tailOf(recorded, skip, base.tap.contactThreshold);
        const SceneSpec noMemory = withMemory(fittedAll, 0.0, 0.0);
        std::vector<double> nulls;
        for (int b = 0; b < std::max(settings.bootstrapReplicates, 10); ++b)
            nulls.push_back(
                tailOf(simulateAt(noMemory, model, recorded,
                                  settings.seed + 80000 + static_cast<std::uint64_t>(b)),
                       skip, base.tap.contactThreshold)
                    .early);
        const double stat = zAbove(target.early, nulls);
        memoryListed = target.taps >= 10 && stat > z;
        fit.choices.push_back(
            {"viscoelastic_memory", memoryListed,
             "what the touching taps' totals still read over their baseline in the three frames "
             "after the press falls, as a share of the press, less its mean over " +
                 std::to_string(nulls.size()) +
                 " recordings simulated with the fitted scene without memory, over their standard "
                 "deviation (" +
                 std::to_string(target.taps) +
                 " taps with ten frames after the fall), against the one-sided normal quantile "
                 "at the level",
             stat, z, true});
        if (memoryListed) {
            Memory start{0.1, 0.5};
            for (const auto& e : base.effects)
                if (e.name == "viscoelastic_memory") {
                    start.fraction = e.parameters.value("fraction", 0.1);
                    start.tau = e.parameters.value("time_constant_s", 0.5);
                }
            memory = fitMemory(fittedAll, model, recorded, target, skip, start, 6, 3,
                               settings.seed + 81000);
            const SceneSpec atEstimate = withMemory(fittedAll, memory.fraction, memory.tau);
            std::vector<double> fractions, taus;
            for (int b = 0; b < settings.bootstrapReplicates; ++b) {
                const auto replicate =
                    simulateAt(atEstimate, model, recorded,
                               settings.seed + 82000 + static_cast<std::uint64_t>(b));
                const Memory again = fitMemory(
                    fittedAll, model, recorded, tailOf(replicate, skip, base.tap.contactThreshold),
                    skip, memory, 3, 2, settings.seed + 83000 + 10 * static_cast<std::uint64_t>(b));
                fractions.push_back(again.fraction);
                taus.push_back(again.tau);
            }
            parameter("viscoelastic_memory", "fraction", memory.fraction, sd(fractions));
            parameter("viscoelastic_memory", "time_constant_s", memory.tau, sd(taus));
        }
    }
    fit.choices.push_back({"dead_taxel", !fit.deadTaxels.empty(),
                           "a taxel whose readings in taps where the model presses it over 20 "
                           "counts exceed its readings in taps over nothing by under a twentieth "
                           "of the median taxel's",
                           static_cast<double>(fit.deadTaxels.size()), 1.0, true});
    fit.choices.push_back(
        {"adc_quantisation", whole,
         std::string("every reading a whole count; ") +
             (saturates ? "the range read from the readings piled at its top (" +
                              std::to_string(atTop) + " at " + numberText(top) + ", " +
                              std::to_string(belowTop) + " one count below)"
                        : "the range not reached (highest reading " + numberText(top) + ", " +
                              std::to_string(atTop) + " there): max_counts " +
                              numberText(maxCounts) + " kept from the base"),
         whole ? 1.0 : 0.0, 1.0, true});
    if (saturates) parameter("adc_quantisation", "max_counts", maxCounts, 0.0);
    fit.choices.push_back(
        {"intermittent_taxel", blinking.listed,
         "the most readings of one taxel, deep inside a press that the model and the other "
         "taxels both hold, under a quarter of its median over that press while most of the "
         "frame's pressed taxels are not (a live taxel's noise gives none)",
         static_cast<double>(blinking.mostLow), static_cast<double>(kBlinkReadings), true});
    if (blinking.listed) {
        // Both positive and read from few spells: intervals on the log scale.
        auto positive = [&](const char* name, double value, const std::vector<double>& reps) {
            std::vector<double> logs;
            for (double r : reps) logs.push_back(std::log(std::max(r, 1e-6)));
            const double seLog = sd(logs);
            fit.parameters.push_back({"intermittent_taxel", name, value, value * seLog,
                                      value * std::exp(-1.96 * seLog),
                                      value * std::exp(1.96 * seLog)});
        };
        positive("off_fraction", blinking.offFraction, offFractions);
        positive("mean_off_s", blinking.meanOff_s, offSpells);
        fit.intermittentTaxels = blinking.taxels;
    }
    for (const auto& e : base.effects)
        if (!estimatedHere(e.name) && e.name != "viscoelastic_memory" &&
            e.name != "contact_latency" && e.name != "stage_error" && e.name != "crosstalk")
            fit.choices.push_back({e.name, true,
                                   "not identifiable from taps by this fit: kept as the base scene "
                                   "lists it",
                                   0.0, 0.0, false});

    fit.fitted = withMemory(sceneWith(base, chosen, whole, maxCounts, fit.deadTaxels,
                                      fit.deadReading, driftTemplate, c.blink),
                            memoryListed ? memory.fraction : 0.0, memory.tau);
    // The stage's error last, against the scene as fitted.
    if (const auto stageSigma =
            readStageError(given, base, model, recorded, skip, maxCounts, settings, z, fit))
        fit.fitted = withEffect(fit.fitted, "stage_error", Json{{"sigma_mm", *stageSigma}});

    // Goodness of fit, per taxel: recorded against simulated with the fitted scene, beside what
    // two simulations of it show.
    for (int b = 0; b < 2 * 10; ++b)
        fit.simulated.push_back(simulateAt(fit.fitted, model, recorded,
                                           settings.seed + 20000 + static_cast<std::uint64_t>(b)));
    const auto& pairs = fit.simulated;
    for (int k = 0; k < K; ++k) {
        TaxelFit tf;
        tf.taxel = k;
        const auto rec = readings(recorded, k), sim = readings(fit.simulated.front(), k);
        tf.ks = ksDistance(rec, sim);
        tf.wasserstein = wasserstein(rec, sim);
        std::vector<double> null;
        for (std::size_t b = 0; b + 1 < pairs.size(); b += 2)
            null.push_back(ksDistance(readings(pairs[b], k), readings(pairs[b + 1], k)));
        std::sort(null.begin(), null.end());
        tf.ksMatch = null[static_cast<std::size_t>(std::ceil(0.95 * null.size())) - 1];
        tf.matches = tf.ks <= tf.ksMatch;
        fit.taxels.push_back(tf);
    }
    return fit;
}

Figure6Comparison compareFigure6(const ExperimentSpec& spec, const std::vector<CollectedTap>& taps,
                                 const SceneFit& fit) {
    auto validationOf = [&](const std::vector<CollectedTap>& recorded) {
        RunOptions options;
        options.simulated = &simulatedRigs();
        options.recordedTaps = &recorded;
        return runExperiment(spec, options).validation;
    };
    Figure6Comparison c;
    c.recorded = validationOf(taps);
    std::vector<CollectedTap> simulated = taps;
    for (std::size_t r = 0; r < fit.simulated.size(); ++r) {
        for (std::size_t i = 0; i < simulated.size(); ++i) {
            simulated[i].record.tap = fit.simulated[r][i].tap;
            simulated[i].record.ending = fit.simulated[r][i].ending;
        }
        if (r == 0) c.firstSimulated = simulated;
        c.simulated.push_back(validationOf(simulated));
    }
    if (c.simulated.empty()) return c;
    c.angleLeast = c.positionLeast = 1e300;
    c.angleLargest = c.positionLargest = -1e300;
    for (const auto& v : c.simulated) {
        c.angleMean += v.angleError_deg / static_cast<double>(c.simulated.size());
        c.positionMean += v.positionError_mm / static_cast<double>(c.simulated.size());
        c.angleLeast = std::min(c.angleLeast, v.angleError_deg);
        c.angleLargest = std::max(c.angleLargest, v.angleError_deg);
        c.positionLeast = std::min(c.positionLeast, v.positionError_mm);
        c.positionLargest = std::max(c.positionLargest, v.positionError_mm);
    }
    c.recordedInsideRange = c.recorded.angleError_deg >= c.angleLeast &&
                            c.recorded.angleError_deg <= c.angleLargest &&
                            c.recorded.positionError_mm >= c.positionLeast &&
                            c.recorded.positionError_mm <= c.positionLargest;
    return c;
}

bool SceneFit::lists(const std::string& effect) const {
    for (const auto& c : choices)
        if (c.effect == effect) return c.listed;
    return false;
}

std::string fittedSceneJson(const SceneFit& fit) {
    return sceneToJson(fit.fitted).dump(2) + "\n";
}

}  // namespace activetouch
