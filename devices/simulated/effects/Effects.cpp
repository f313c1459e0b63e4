// The effects of the simulated rig. Parameters are all required in a scene (no silent defaults);
// `typical` values are what the GUI proposes and what the paper scene uses unless it says why not.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>

#include "core/common/Avx2Clones.h"
#include "core/rig/Rig.h"
#include "devices/simulated/effects/Effect.h"
#include "devices/simulated/effects/EffectSets.h"

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
        // Both residuals decay by the same factor from one sample to the next: three exp() a
        // tap rather than two a sample.
        const int K = tap.taxels;
        const double step = std::exp(-c.samplePeriod_s / tau_);
        double prev = std::isfinite(lastRelease_)
                          ? fraction_ * std::exp(-(c.startTime_s - lastRelease_) / tau_)
                          : 0.0;
        double own = -1.0;  // not yet released
        for (int t = 0; t < tap.sampleCount(); ++t, prev *= step) {
            const double local = t * c.samplePeriod_s;
            if (local > c.release_s)
                own = own < 0.0 ? fraction_ * std::exp(-(local - c.release_s) / tau_) : own * step;
            const double ownNow = own < 0.0 ? 0.0 : own;
            for (int k = 0; k < K; ++k)
                tap.at(t, k) +=
                    prev * lastHold_[static_cast<std::size_t>(k)] + ownNow * c.holdPressures[k];
        }
        for (int k = 0; k < K; ++k) lastHold_[static_cast<std::size_t>(k)] = c.holdPressures[k];
        lastRelease_ = c.startTime_s + c.release_s;
    }

private:
    double fraction_, tau_;
    std::vector<double> lastHold_;
    double lastRelease_ = -INFINITY;
};

/// BaselineDrift's walk over `frames` frames of K taxels: each taxel's drift takes its step
/// (scale * z), the reading is the pressure plus the drift less the compensation's estimate, and
/// the estimate closes the fraction `touch` (above the threshold) or `free` of the gap. Taxels are
/// independent: cloned for AVX2, several taxels to an instruction, the same values in either
/// clone (no FMA).
ACTIVETOUCH_AVX2_CLONES void driftFrames(double* __restrict pressures, const double* __restrict z,
                                         std::size_t frames, std::size_t K, double scale,
                                         double threshold, double touch, double free,
                                         double* __restrict drift, double* __restrict estimate) {
    for (std::size_t t = 0; t < frames; ++t) {
        double* __restrict p = pressures + t * K;
        const double* __restrict zt = z + t * K;
        for (std::size_t k = 0; k < K; ++k) {
            drift[k] += scale * zt[k];
            const double d = p[k] + drift[k] - estimate[k];
            estimate[k] += (d > threshold ? touch : free) * d;
            p[k] = d > 0.0 ? d : 0.0;
        }
    }
}

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
            if (steps > 0) {
                idle_.assign(drift_.size() * static_cast<std::size_t>(steps), 0.0);
                walk(idle_.data(), static_cast<std::size_t>(steps), gap / steps);
            }
        }
        walk(tap.samples.data(), static_cast<std::size_t>(tap.sampleCount()), c.samplePeriod_s);
        lastTime_ = c.startTime_s + tap.sampleCount() * c.samplePeriod_s;
    }

private:
    /// `frames` frames of every taxel's pressure, dt apart, in place: the drift's random walk
    /// added, the compensation's estimate taken off and nudged toward the reading. skinManager
    /// nudges by gain * 0.02 * d / threshold every 20 ms (the touch gain while d is above the
    /// threshold); over dt that compounds to a fraction 1 - (1 - rate)^(dt / 0.02) of the gap,
    /// never overshooting it.
    void walk(double* pressures, std::size_t frames, double dt) {
        const std::size_t K = drift_.size();
        steps_.resize(frames * K);
        rng_.normals(steps_.data(), steps_.size());
        const double scale = rate_ * std::sqrt(dt);
        const double touch = nudge(touchGain_, dt), free = nudge(freeGain_, dt);
        driftFrames(pressures, steps_.data(), frames, K, scale, threshold_, touch, free,
                    drift_.data(), estimate_.data());
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
    std::vector<double> drift_, estimate_, steps_, idle_;
    RandomStream rng_;
    double lastTime_ = -INFINITY;
};

/// Gaussian electronic noise on every sample; the compensated output cannot go below 0.
class TaxelNoise final : public Effect {
public:
    TaxelNoise(double sigma, RandomStream rng)
        : Effect("taxel_noise", Acts::Signal, 50), sigma_(sigma), rng_(rng) {}
    void shapeSignal(Tap& tap, const SignalContext&) override {
        draws_.resize(tap.samples.size());
        rng_.normals(draws_.data(), draws_.size());
        double* __restrict v = tap.samples.data();
        const double* __restrict z = draws_.data();
        const double sigma = sigma_;
        for (std::size_t i = 0; i < draws_.size(); ++i) v[i] = std::max(0.0, v[i] + sigma * z[i]);
    }

private:
    double sigma_;
    RandomStream rng_;
    std::vector<double> draws_;
};

/// The 8-bit converter: whole counts, saturating at the top of the range.
class AdcQuantisation final : public Effect {
public:
    explicit AdcQuantisation(double maxCounts)
        : Effect("adc_quantisation", Acts::Signal, 60), max_(maxCounts) {}
    void shapeSignal(Tap& tap, const SignalContext&) override {
        // Clamped to the range, then rounded to the nearest count by adding and taking off 2^52
        // (a double has no fraction bits there; a tie goes to the even count): no library
        // call per sample, several samples to an instruction.
        const double top = max_;
        for (double& v : tap.samples) {
            const double x = std::min(v > 0.0 ? v : 0.0, top);
            v = std::min((x + 0x1p52) - 0x1p52, top);
        }
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
                     return std::make_unique<TaxelNoise>(f.number("sigma_counts", 0.0, 50.0), r);
                 }});
    c.push_back(
        {"baseline_drift",
         "Random-walk drift of each taxel's baseline with skinManager-style compensation.",
         {{"rate_counts_per_sqrt_s", "random-walk drift, counts per sqrt(second)", 0.0, 20.0, 0.5},
          {"touch_threshold_counts", "compensation's touch threshold, counts", 0.1, 100.0, 2.0},
          {"free_gain", "compensation gain without touch", 0.0, 1.0, 0.2},
          {"touch_gain", "compensation gain in touch", 0.0, 1.0, 0.05}},
         false,
         [](const JsonFields& f, const M& m, RandomStream r) {
             return std::make_unique<BaselineDrift>(
                 f.number("rate_counts_per_sqrt_s", 0.0, 20.0),
                 f.number("touch_threshold_counts", 0.1, 100.0), f.number("free_gain", 0.0, 1.0),
                 f.number("touch_gain", 0.0, 1.0), m.taxelCount(), r);
         }});
    c.push_back({"adc_quantisation",
                 "8-bit conversion: readings rounded to whole counts and saturated.",
                 {{"max_counts", "saturation level, counts", 1.0, 255.0, 255.0}},
                 false,
                 [](const JsonFields& f, const M&, RandomStream) {
                     return std::make_unique<AdcQuantisation>(f.number("max_counts", 1.0, 255.0));
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
                 {{"fraction", "residual right after release, fraction of the held pressure", 0.0,
                   1.0, 0.1},
                  {"time_constant_s", "decay time constant, seconds", 0.01, 60.0, 0.5}},
                 false,
                 [](const JsonFields& f, const M& m, RandomStream) {
                     return std::make_unique<ViscoelasticMemory>(
                         f.number("fraction", 0.0, 1.0), f.number("time_constant_s", 0.01, 60.0),
                         m.taxelCount());
                 }});
}

/// The stream's faults: dropouts.
void addStreamEffects(std::vector<EffectDescription>& c) {
    c.push_back({"link_dropout",
                 "The fingertip's stream drops during a tap, as a flaky cable or network "
                 "does: the tap fails with a device error (for trying fault handling).",
                 {{"probability_per_tap", "chance that a tap's stream drops", 0.0, 1.0, 0.0}},
                 false,
                 [](const JsonFields& f, const M&, RandomStream r) {
                     return std::make_unique<LinkDropout>(f.number("probability_per_tap", 0.0, 1.0),
                                                          r);
                 }});
}

}  // namespace

const std::vector<EffectDescription>& effectCatalogue() {
    static const std::vector<EffectDescription> catalogue = [] {
        std::vector<EffectDescription> c;
        addSignalEffects(c);
        addTaxelEffects(c);
        addStreamEffects(c);
        return c;
    }();
    return catalogue;
}

}  // namespace activetouch
