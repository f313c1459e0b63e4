// The effects of the simulated rig. Parameters are all required in a scene (no silent defaults);
// `typical` values are what the GUI proposes and what the paper scene uses unless it says why not.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>

#include "core/rig/Rig.h"
#include "devices/simulated/effects/Effect.h"

namespace activetouch {
namespace {

std::mutex countsMutex;
std::map<std::string, int>& counts() {
    static std::map<std::string, int> c;
    return c;
}

/// The fingertip's stream dropping mid-tap, as a loose cable, a USB hub or a busy network does on
/// the real rig: with the given probability a tap fails with the device error the YARP reader
/// gives, so that how a run, a trial or a sweep over seeds handles a device fault can be tried
/// on the simulated rig. The probability is the scene's; which tap fails comes from the seed.
class LinkDropout final : public Effect {
public:
    LinkDropout(double probability, RandomStream rng)
        : Effect("link_dropout", Acts::Signal, 0), probability_(probability), rng_(rng) {}
    void shapeSignal(Tap&, const SignalContext& c) override {
        if (rng_.uniform() < probability_)
            throw RigError("simulated fingertip: the stream dropped during the tap at " +
                           std::to_string(c.startTime_s) +
                           " s of robot time (link_dropout); reconnect the fingertip");
    }

private:
    double probability_;
    RandomStream rng_;
};

/// Gaussian stage positioning error per move (the paper's stage: about 20 um).
class StageError final : public Effect {
public:
    StageError(double sigma, RandomStream rng)
        : Effect("stage_error", Acts::Pose), sigma_(sigma), rng_(rng) {}
    Vec2 perturbPose(Vec2 p) override {
        return {p.x + rng_.normal(0, sigma_), p.y + rng_.normal(0, sigma_)};
    }

private:
    double sigma_;
    RandomStream rng_;
};

/// The reflex stops the tapper only after a latency, so it keeps pressing (paper: 20 ms).
class ContactLatency final : public Effect {
public:
    explicit ContactLatency(double latency)
        : Effect("contact_latency", Acts::Mechanics), latency_(latency) {}
    double reflexLatency_s() const override { return latency_; }

private:
    double latency_;
};

/// The pad relaxes slowly after being pressed: a residual that decays with time after release,
/// carried into the next tap (why the paper waits 2 s between taps).
class ViscoelasticMemory final : public Effect {
public:
    ViscoelasticMemory(double fraction, double tau, int taxels)
        : Effect("viscoelastic_memory", Acts::Signal, 10),
          fraction_(fraction),
          tau_(tau),
          lastHold_(static_cast<std::size_t>(taxels), 0.0) {}
    void shapeSignal(Tap& tap, const SignalContext& c) override {
        const int K = tap.taxels;
        for (int t = 0; t < tap.sampleCount(); ++t) {
            const double now = c.startTime_s + t * c.samplePeriod_s;
            const double sincePrev = now - lastRelease_;
            const double prev =
                std::isfinite(lastRelease_) ? fraction_ * std::exp(-sincePrev / tau_) : 0.0;
            const double local = t * c.samplePeriod_s;
            const double own =
                local > c.release_s ? fraction_ * std::exp(-(local - c.release_s) / tau_) : 0.0;
            for (int k = 0; k < K; ++k)
                tap.at(t, k) +=
                    prev * lastHold_[static_cast<std::size_t>(k)] + own * c.holdPressures[k];
        }
        for (int k = 0; k < K; ++k) lastHold_[static_cast<std::size_t>(k)] = c.holdPressures[k];
        lastRelease_ = c.startTime_s + c.release_s;
    }

private:
    double fraction_, tau_;
    std::vector<double> lastHold_;
    double lastRelease_ = -INFINITY;
};

/// Capacitive coupling: each taxel also reads a fraction of its neighbours within a radius.
class Crosstalk final : public Effect {
public:
    Crosstalk(double coupling, double radius, const FingertipContactModel& model)
        : Effect("crosstalk", Acts::Signal, 20), K_(model.taxelCount()) {
        const auto& p = model.projectedTaxels();
        for (int i = 0; i < K_; ++i)
            for (int j = 0; j < K_; ++j)
                if (i != j && distance(p[static_cast<std::size_t>(i)],
                                       p[static_cast<std::size_t>(j)]) <= radius)
                    pairs_.push_back({i, j});
        coupling_ = coupling;
    }
    void shapeSignal(Tap& tap, const SignalContext&) override {
        std::vector<double> frame(static_cast<std::size_t>(K_));
        for (int t = 0; t < tap.sampleCount(); ++t) {
            std::copy(tap.frame(t), tap.frame(t) + K_, frame.begin());
            for (const auto& [to, from] : pairs_)
                tap.at(t, to) += coupling_ * frame[static_cast<std::size_t>(from)];
        }
    }

private:
    int K_;
    double coupling_ = 0.0;
    std::vector<std::pair<int, int>> pairs_;  // (reader, neighbour)
};

/// Each taxel's own sensitivity: real skins differ taxel to taxel, so the same pressure reads
/// higher on some than on others. The gains are log-normal around 1 (the log's standard
/// deviation is `spread`) and belong to the fingertip, not to a tap or a trial: they are drawn
/// from `fingertip_seed`, so training and trials, and every seed of a sweep, use the same
/// fingertip unless the scene names another.
class TaxelGain final : public Effect {
public:
    TaxelGain(double spread, double fingertipSeed, int taxels)
        : Effect("taxel_gain", Acts::Signal, 25) {
        RandomStream draw =
            RandomStream::derived(static_cast<std::uint64_t>(fingertipSeed), "taxel_gain");
        for (int k = 0; k < taxels; ++k) gains_.push_back(std::exp(spread * draw.normal()));
    }
    explicit TaxelGain(std::vector<double> gains)
        : Effect("taxel_gain", Acts::Signal, 25), gains_(std::move(gains)) {}
    void shapeSignal(Tap& tap, const SignalContext&) override {
        for (int t = 0; t < tap.sampleCount(); ++t)
            for (int k = 0; k < tap.taxels; ++k)
                tap.at(t, k) *= gains_[static_cast<std::size_t>(k)];
    }

private:
    std::vector<double> gains_;
};

/// A taxel that saturates and then recovers slowly: above `level` it reads `level`, and once
/// the pressure falls back its reading decays from the level with time constant `tau` instead
/// of following at once, across taps too (the lingering reading of an overloaded skin).
class SaturationRecovery final : public Effect {
public:
    SaturationRecovery(double level, double tau, int taxels)
        : Effect("saturation_recovery", Acts::Signal, 27),
          level_(level),
          tau_(tau),
          lastSaturated_(static_cast<std::size_t>(taxels), -INFINITY) {}
    void shapeSignal(Tap& tap, const SignalContext& c) override {
        for (int t = 0; t < tap.sampleCount(); ++t) {
            const double now = c.startTime_s + t * c.samplePeriod_s;
            for (int k = 0; k < tap.taxels; ++k) {
                double& since = lastSaturated_[static_cast<std::size_t>(k)];
                double& v = tap.at(t, k);
                if (v >= level_) {
                    v = level_;
                    since = now;
                } else if (std::isfinite(since)) {
                    v = std::max(v, level_ * std::exp(-(now - since) / tau_));
                }
            }
        }
    }

private:
    double level_, tau_;
    std::vector<double> lastSaturated_;  ///< robot time each taxel was last saturated
};

/// Taxels that blink: each listed taxel switches between working and reading a fixed value
/// (0: dropping out; a high value: a spurious activation) as a two-state Markov process in
/// robot time, off a long-run `off_fraction` of the time for `mean_off_s` on average.
class IntermittentTaxel final : public Effect {
public:
    IntermittentTaxel(std::vector<int> taxels, double offFraction, double meanOff, double reading,
                      RandomStream rng)
        : Effect("intermittent_taxel", Acts::Signal, 35),
          taxels_(std::move(taxels)),
          onRate_(1.0 / meanOff),
          offRate_(offFraction >= 1.0 ? INFINITY : offFraction / (1.0 - offFraction) / meanOff),
          stationaryOff_(offFraction),
          reading_(reading),
          off_(taxels_.size(), false),
          rng_(rng) {}
    void shapeSignal(Tap& tap, const SignalContext& c) override {
        // Between taps the chain runs on unobserved: the chance of being off after a gap is the
        // two-state chain's, relaxing to the long-run fraction at rate on + off.
        const double gap = std::isfinite(lastTime_) ? c.startTime_s - lastTime_ : INFINITY;
        const double relax = std::isfinite(offRate_) ? std::exp(-(onRate_ + offRate_) * gap) : 0.0;
        for (std::size_t i = 0; i < taxels_.size(); ++i) {
            const double start = off_[i] ? 1.0 : 0.0;
            off_[i] = rng_.uniform() < stationaryOff_ + (start - stationaryOff_) * relax;
        }
        const double dt = c.samplePeriod_s;
        const double pOff = std::isfinite(offRate_) ? 1.0 - std::exp(-offRate_ * dt) : 1.0;
        const double pOn = 1.0 - std::exp(-onRate_ * dt);
        for (int t = 0; t < tap.sampleCount(); ++t)
            for (std::size_t i = 0; i < taxels_.size(); ++i) {
                if (t > 0) off_[i] = off_[i] ? !(rng_.uniform() < pOn) : rng_.uniform() < pOff;
                if (off_[i]) tap.at(t, taxels_[i]) = reading_;
            }
        lastTime_ = c.startTime_s + tap.sampleCount() * dt;
    }

private:
    std::vector<int> taxels_;
    double onRate_, offRate_, stationaryOff_, reading_;
    std::vector<bool> off_;
    RandomStream rng_;
    double lastTime_ = -INFINITY;
};

/// Taxels that never respond (or are stuck at a reading).
class DeadTaxel final : public Effect {
public:
    DeadTaxel(std::vector<int> taxels, double reading)
        : Effect("dead_taxel", Acts::Signal, 30), taxels_(std::move(taxels)), reading_(reading) {}
    void shapeSignal(Tap& tap, const SignalContext&) override {
        for (int t = 0; t < tap.sampleCount(); ++t)
            for (int k : taxels_) tap.at(t, k) = reading_;
    }

private:
    std::vector<int> taxels_;
    double reading_;
};

/// Thermal drift of each taxel's baseline (a random walk) and skinManager's compensation, which
/// nudges its baseline estimate toward the reading by gain * 0.02 * d / threshold per sample
/// (docs/protocols.md §4): compensation leaves a residual and slowly eats into a sustained press.
class BaselineDrift final : public Effect {
public:
    BaselineDrift(double rate, double threshold, double freeGain, double touchGain, int taxels,
                  RandomStream rng)
        : Effect("baseline_drift", Acts::Signal, 40),
          rate_(rate),
          threshold_(threshold),
          freeGain_(freeGain),
          touchGain_(touchGain),
          drift_(static_cast<std::size_t>(taxels), 0.0),
          estimate_(static_cast<std::size_t>(taxels), 0.0),
          rng_(rng) {}
    void shapeSignal(Tap& tap, const SignalContext& c) override {
        // The time since the previous tap passes without touch, in steps of at most a quarter
        // second: the drift is a random walk (its variance only depends on the total time) and
        // the compensation a slow first-order filter, so coarse steps keep both statistics.
        if (std::isfinite(lastTime_)) {
            const double gap = c.startTime_s - lastTime_;
            const int steps = std::clamp(static_cast<int>(std::ceil(gap / 0.25)), 0, 400);
            const double dt = steps > 0 ? gap / steps : 0.0;
            for (int s = 0; s < steps; ++s)
                for (std::size_t k = 0; k < drift_.size(); ++k) step(k, 0.0, dt);
        }
        for (int t = 0; t < tap.sampleCount(); ++t)
            for (int k = 0; k < tap.taxels; ++k)
                tap.at(t, k) = step(static_cast<std::size_t>(k), tap.at(t, k), c.samplePeriod_s);
        lastTime_ = c.startTime_s + tap.sampleCount() * c.samplePeriod_s;
    }

private:
    double step(std::size_t k, double pressure, double dt) {
        drift_[k] += rate_ * std::sqrt(dt) * rng_.normal();
        const double d = pressure + drift_[k] - estimate_[k];
        const double gain = d > threshold_ ? touchGain_ : freeGain_;
        // skinManager nudges by gain * 0.02 * d / threshold every 20 ms; over dt that compounds
        // to a fraction 1 - (1 - rate)^(dt / 0.02) of the gap, never overshooting it.
        estimate_[k] += nudge(gain, dt) * d;
        return std::max(0.0, d);
    }
    /// The fraction of the gap closed over dt: skinManager's per-20-ms nudge compounded.
    double nudge(double gain, double dt) {
        double& cached = gain == touchGain_ ? touchNudge_ : freeNudge_;
        double& cachedDt = gain == touchGain_ ? touchDt_ : freeDt_;
        if (dt != cachedDt) {
            cachedDt = dt;
            cached = 1.0 - std::pow(1.0 - std::min(1.0, gain * 0.02 / threshold_), dt / 0.02);
        }
        return cached;
    }
    double rate_, threshold_, freeGain_, touchGain_;
    double freeNudge_ = 0, touchNudge_ = 0, freeDt_ = -1, touchDt_ = -1;
    std::vector<double> drift_, estimate_;
    RandomStream rng_;
    double lastTime_ = -INFINITY;
};

/// Gaussian electronic noise on every sample; the compensated output cannot go below 0.
class TaxelNoise final : public Effect {
public:
    TaxelNoise(double sigma, RandomStream rng)
        : Effect("taxel_noise", Acts::Signal, 50), sigma_(sigma), rng_(rng) {}
    void shapeSignal(Tap& tap, const SignalContext&) override {
        for (double& v : tap.samples) v = std::max(0.0, v + sigma_ * rng_.normal());
    }

private:
    double sigma_;
    RandomStream rng_;
};

/// The 8-bit converter: whole counts, saturating at the top of the range.
class AdcQuantisation final : public Effect {
public:
    explicit AdcQuantisation(double maxCounts)
        : Effect("adc_quantisation", Acts::Signal, 60), max_(maxCounts) {}
    void shapeSignal(Tap& tap, const SignalContext&) override {
        for (double& v : tap.samples) v = std::clamp(std::round(v), 0.0, max_);
    }

private:
    double max_;
};

}  // namespace

Effect::Effect(std::string name, Acts acts, int order)
    : name_(std::move(name)), acts_(acts), order_(order) {
    std::lock_guard lock(countsMutex);
    ++counts()[name_];
}

int Effect::constructedCount(const std::string& name) {
    std::lock_guard lock(countsMutex);
    auto it = counts().find(name);
    return it == counts().end() ? 0 : it->second;
}

namespace {

using M = FingertipContactModel;

/// The effects of the signal: noise, drift, quantisation, timing, the stage and the skin's memory.
void addSignalEffects(std::vector<EffectDescription>& c) {
    c.push_back({"taxel_noise",
                 "Gaussian noise on every sample of every taxel, clipped at 0 counts.",
                 {{"sigma_counts", "standard deviation, counts", 0.0, 50.0, 1.5}},
                 false,
                 [](const JsonFields& f, const M&, RandomStream r) {
                     return std::make_unique<TaxelNoise>(f.number("sigma_counts", 0.0, 50.0),
                                                         r);
                 }});
    c.push_back(
        {"baseline_drift",
         "Random-walk drift of each taxel's baseline with skinManager-style compensation.",
         {{"rate_counts_per_sqrt_s", "random-walk drift, counts per sqrt(second)", 0.0, 20.0,
           0.5},
          {"touch_threshold_counts", "compensation's touch threshold, counts", 0.1, 100.0, 2.0},
          {"free_gain", "compensation gain without touch", 0.0, 1.0, 0.2},
          {"touch_gain", "compensation gain in touch", 0.0, 1.0, 0.05}},
         false,
         [](const JsonFields& f, const M& m, RandomStream r) {
             return std::make_unique<BaselineDrift>(
                 f.number("rate_counts_per_sqrt_s", 0.0, 20.0),
                 f.number("touch_threshold_counts", 0.1, 100.0),
                 f.number("free_gain", 0.0, 1.0), f.number("touch_gain", 0.0, 1.0),
                 m.taxelCount(), r);
         }});
    c.push_back({"adc_quantisation",
                 "8-bit conversion: readings rounded to whole counts and saturated.",
                 {{"max_counts", "saturation level, counts", 1.0, 255.0, 255.0}},
                 false,
                 [](const JsonFields& f, const M&, RandomStream) {
                     return std::make_unique<AdcQuantisation>(
                         f.number("max_counts", 1.0, 255.0));
                 }});
    c.push_back({"contact_latency",
                 "The contact reflex stops the tapper only after a latency.",
                 {{"latency_s", "reflex latency, seconds", 0.0, 0.5, 0.02}},
                 false,
                 [](const JsonFields& f, const M&, RandomStream) {
                     return std::make_unique<ContactLatency>(f.number("latency_s", 0.0, 0.5));
                 }});
    c.push_back({"stage_error",
                 "Gaussian positioning error of the XY stage on each move.",
                 {{"sigma_mm", "standard deviation per axis, mm", 0.0, 2.0, 0.02}},
                 false,
                 [](const JsonFields& f, const M&, RandomStream r) {
                     return std::make_unique<StageError>(f.number("sigma_mm", 0.0, 2.0), r);
                 }});
    c.push_back({"viscoelastic_memory",
                 "The pad keeps a decaying residual of recent presses.",
                 {{"fraction", "residual right after release, fraction of the held pressure",
                   0.0, 1.0, 0.1},
                  {"time_constant_s", "decay time constant, seconds", 0.01, 60.0, 0.5}},
                 false,
                 [](const JsonFields& f, const M& m, RandomStream) {
                     return std::make_unique<ViscoelasticMemory>(
                         f.number("fraction", 0.0, 1.0),
                         f.number("time_constant_s", 0.01, 60.0), m.taxelCount());
                 }});
}

/// The effects of single taxels and of the link: crosstalk, dead taxels, per-taxel gains,
/// saturation with recovery, intermittent taxels and dropouts.
void addTaxelEffects(std::vector<EffectDescription>& c) {
    c.push_back({"crosstalk",
                 "Each taxel also reads a fraction of its neighbours' pressure.",
                 {{"coupling", "fraction of each neighbour's pressure", 0.0, 0.5, 0.05},
                  {"radius_mm", "neighbours within this distance on the contact plane, mm", 0.0,
                   30.0, 4.5}},
                 false,
                 [](const JsonFields& f, const M& m, RandomStream) {
                     return std::make_unique<Crosstalk>(f.number("coupling", 0.0, 0.5),
                                                        f.number("radius_mm", 0.0, 30.0), m);
                 }});
    c.push_back({"dead_taxel",
                 "Listed taxels read a fixed value (0 = dead) whatever the contact.",
                 {{"reading_counts", "the stuck reading, counts", 0.0, 255.0, 0.0}},
                 true,
                 [](const JsonFields& f, const M& m, RandomStream) {
                     return std::make_unique<DeadTaxel>(effectTaxelList(f, m.taxelCount()),
                                                        f.number("reading_counts", 0.0, 255.0));
                 }});
    c.push_back(
        {"taxel_gain",
         "Each taxel's own sensitivity: gains log-normal around 1, fixed for the "
         "fingertip (or 'gains', one per taxel, as measured).",
         {{"spread", "standard deviation of the gains' logarithm", 0.0, 1.0, 0.2},
          {"fingertip_seed", "which fingertip's gains (any whole number)", 0.0, 1e9, 1.0}},
         false,
         [](const JsonFields& f, const M& m, RandomStream) -> std::unique_ptr<Effect> {
             if (f.has("gains"))
                 return std::make_unique<TaxelGain>(effectGainList(f, m.taxelCount()));
             const double seed = f.number("fingertip_seed", 0.0, 1e9);
             if (seed != std::floor(seed)) f.fail("fingertip_seed", "give a whole number");
             return std::make_unique<TaxelGain>(f.number("spread", 0.0, 1.0), seed,
                                                m.taxelCount());
         }});
    c.back().takesGainList = true;
    c.push_back(
        {"saturation_recovery",
         "Taxels saturate at a level and, once released, recover from it slowly.",
         {{"saturation_counts", "the level a taxel saturates at, counts", 1.0, 1000.0, 150.0},
          {"recovery_s", "time constant of the recovery, seconds", 0.001, 60.0, 1.0}},
         false,
         [](const JsonFields& f, const M& m, RandomStream) {
             return std::make_unique<SaturationRecovery>(
                 f.number("saturation_counts", 1.0, 1000.0),
                 f.number("recovery_s", 0.001, 60.0), m.taxelCount());
         }});
    c.push_back(
        {"intermittent_taxel",
         "Listed taxels blink: off (reading a fixed value) for a share of the time, at "
         "random.",
         {{"off_fraction", "long-run share of the time a taxel is off", 0.0, 1.0, 0.1},
          {"mean_off_s", "mean length of an off spell, seconds", 0.001, 60.0, 0.1},
          {"reading_counts", "what an off taxel reads (0: nothing), counts", 0.0, 255.0, 0.0}},
         true,
         [](const JsonFields& f, const M& m, RandomStream r) {
             return std::make_unique<IntermittentTaxel>(
                 effectTaxelList(f, m.taxelCount()), f.number("off_fraction", 0.0, 1.0),
                 f.number("mean_off_s", 0.001, 60.0), f.number("reading_counts", 0.0, 255.0),
                 r);
         }});
    c.push_back({"link_dropout",
                 "The fingertip's stream drops during a tap, as a flaky cable or network "
                 "does: the tap fails with a device error (for trying fault handling).",
                 {{"probability_per_tap", "chance that a tap's stream drops", 0.0, 1.0, 0.0}},
                 false,
                 [](const JsonFields& f, const M&, RandomStream r) {
                     return std::make_unique<LinkDropout>(
                         f.number("probability_per_tap", 0.0, 1.0), r);
                 }});
}

}  // namespace

const std::vector<EffectDescription>& effectCatalogue() {
    static const std::vector<EffectDescription> catalogue = [] {
        std::vector<EffectDescription> c;
        addSignalEffects(c);
        addTaxelEffects(c);
        return c;
    }();
    return catalogue;
}

}  // namespace activetouch
