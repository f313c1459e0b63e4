// The effects of single taxels of the simulated rig (docs/simulated-rig.md): what one taxel reads
// differs from the ideal pressure under it. Parameters as in Effects.cpp: all required.
#include <algorithm>
#include <cmath>

#include "core/rig/Rig.h"
#include "devices/simulated/effects/EffectSets.h"

namespace activetouch {
namespace {

/// Capacitive coupling: each taxel also reads a fraction of its neighbours within a radius.
class Crosstalk final : public Effect {
public:
    Crosstalk(double coupling, double radius, const FingertipContactModel& model)
        : Effect("crosstalk", Acts::Signal, 20),
          K_(model.taxelCount()),
          coupling_(coupling),
          first_(static_cast<std::size_t>(K_) + 1, 0) {
        const auto& p = model.projectedTaxels();
        for (int i = 0; i < K_; ++i) {
            for (int j = 0; j < K_; ++j)
                if (i != j && distance(p[static_cast<std::size_t>(i)],
                                       p[static_cast<std::size_t>(j)]) <= radius)
                    neighbours_.push_back(j);
            first_[static_cast<std::size_t>(i) + 1] = neighbours_.size();
        }
    }
    void shapeSignal(Tap& tap, const SignalContext&) override {
        // Taxel by taxel over the whole tap (each taxel's samples in a row of their own), so that
        // one instruction adds a neighbour to several samples; each sample's neighbours are still
        // summed one by one in the reader's order, the same values as frame by frame.
        const auto K = static_cast<std::size_t>(K_);
        const auto T = static_cast<std::size_t>(tap.sampleCount());
        rows_.resize(K * T);
        sums_.resize(T);
        double* __restrict rows = rows_.data();
        double* __restrict sums = sums_.data();
        double* __restrict f = tap.samples.data();
        for (std::size_t t = 0; t < T; ++t)
            for (std::size_t k = 0; k < K; ++k) rows[k * T + t] = f[t * K + k];
        for (std::size_t i = 0; i < K; ++i) {
            std::fill(sums, sums + T, 0.0);
            for (std::size_t n = first_[i]; n < first_[i + 1]; ++n) {
                const double* __restrict row = rows + neighbours_[n] * T;
                for (std::size_t t = 0; t < T; ++t) sums[t] += row[t];
            }
            for (std::size_t t = 0; t < T; ++t) f[t * K + i] += coupling_ * sums[t];
        }
    }

private:
    int K_;
    double coupling_;
    // Each reader's neighbours within the radius: neighbours_[first_[i] .. first_[i + 1]).
    std::vector<std::size_t> first_, neighbours_;
    std::vector<double> rows_, sums_;  // the tap taxel by taxel; one reader's sums
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
        // Nothing to do in a tap that never reaches the level while no taxel is recovering.
        const double level = level_, tau = tau_, start = c.startTime_s, dt = c.samplePeriod_s;
        const bool recovering = std::any_of(lastSaturated_.begin(), lastSaturated_.end(),
                                            [](double s) { return std::isfinite(s); });
        if (!recovering && std::all_of(tap.samples.begin(), tap.samples.end(),
                                       [level](double v) { return v < level; }))
            return;
        double* since = lastSaturated_.data();
        for (int t = 0; t < tap.sampleCount(); ++t) {
            const double now = start + t * dt;
            // Taxels last saturated at the same moment share the decayed level: computed once.
            double sharedSince = NAN, decayed = 0.0;
            double* f = tap.frame(t);
            for (int k = 0; k < tap.taxels; ++k) {
                double& v = f[k];
                if (v >= level) {
                    v = level;
                    since[k] = now;
                } else if (std::isfinite(since[k])) {
                    if (since[k] != sharedSince) {
                        sharedSince = since[k];
                        decayed = level * std::exp(-(now - sharedSince) / tau);
                    }
                    v = std::max(v, decayed);
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
          off_(taxels_.size(), 0),
          rng_(rng) {}
    void shapeSignal(Tap& tap, const SignalContext& c) override {
        // Between taps the chain runs on unobserved: the chance of being off after a gap is the
        // two-state chain's, relaxing to the long-run fraction at rate on + off.
        const double gap = std::isfinite(lastTime_) ? c.startTime_s - lastTime_ : INFINITY;
        const double relax = std::isfinite(offRate_) ? std::exp(-(onRate_ + offRate_) * gap) : 0.0;
        for (std::size_t i = 0; i < taxels_.size(); ++i) {
            const double start = off_[i] ? 1.0 : 0.0;
            off_[i] = rng_.uniform() < stationaryOff_ + (start - stationaryOff_) * relax ? 1 : 0;
        }
        const double dt = c.samplePeriod_s;
        const double pOff = std::isfinite(offRate_) ? 1.0 - std::exp(-offRate_ * dt) : 1.0;
        const double pOn = 1.0 - std::exp(-onRate_ * dt);
        // The chain and its generator in locals for the loop (the tap's samples are written
        // in it), given back after.
        RandomStream draw = rng_;
        int* off = off_.data();
        const double reading = reading_;
        const std::size_t n = taxels_.size();
        for (int t = 0; t < tap.sampleCount(); ++t) {
            double* f = tap.frame(t);
            for (std::size_t i = 0; i < n; ++i) {
                if (t > 0) off[i] = off[i] ? !(draw.uniform() < pOn) : draw.uniform() < pOff;
                if (off[i]) f[taxels_[i]] = reading;
            }
        }
        rng_ = draw;
        lastTime_ = c.startTime_s + tap.sampleCount() * dt;
    }

private:
    std::vector<int> taxels_;
    double onRate_, offRate_, stationaryOff_, reading_;
    std::vector<int> off_;  ///< each listed taxel's state: 1 off, 0 working
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

}  // namespace

void addTaxelEffects(std::vector<EffectDescription>& c) {
    using M = FingertipContactModel;
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
    c.push_back({"taxel_gain",
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
             return std::make_unique<SaturationRecovery>(f.number("saturation_counts", 1.0, 1000.0),
                                                         f.number("recovery_s", 0.001, 60.0),
                                                         m.taxelCount());
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
                 f.number("mean_off_s", 0.001, 60.0), f.number("reading_counts", 0.0, 255.0), r);
         }});
}

}  // namespace activetouch
