// The bootstrap about the moment fit and the choices it informs: noise, drift and gains, each
// listed where its test says so at the level (see fitScene()).
#include "devices/simulated/fit/FitSteps.h"

namespace activetouch::scenefit {

Replicates bootstrapMoments(const FitRun& run, const SceneSpec& fittedAll) {
    const FitContext& c = run.c;
    const SceneFitSettings& settings = run.settings;
    const int K = run.taxels();
    Replicates reps;
    reps.logGains.resize(static_cast<std::size_t>(K));
    const double period = 1.0 / c.base.tap.sampleRate_hz;
    for (int b = 0; b < settings.bootstrapReplicates; ++b) {
        const auto replicate = simulateAt(fittedAll, c.model, c.poses,
                                          settings.seed + 1000 + static_cast<std::uint64_t>(b));
        // A replicate's blinks are read again, so that the gains' spread carries theirs.
        FitContext rc = c;
        Blinking again;
        EffectSpec againEffect;  // the blinking the fit lists (c.blink), as this replicate reads it
        if (run.blinking.listed) {
            again = readBlinking(c.base, c.model, replicate, run.idealTaps, c.skip, period,
                                 settings.seed + 40000 + 100 * static_cast<std::uint64_t>(b),
                                 run.blinking.taxels);
            againEffect = *c.blink;
            againEffect.parameters["off_fraction"] = again.offFraction;
            againEffect.parameters["mean_off_s"] = again.meanOff_s;
            rc.blink = &againEffect;
        }
        const Theta th = fitMoments(rc, momentsOf(replicate, c.masks, c.skip),
                                    settings.seed + 5000 + static_cast<std::uint64_t>(b));
        reps.sigmas.push_back(th.sigma);
        reps.rates.push_back(th.rate);
        if (run.blinking.listed) {
            reps.offFractions.push_back(again.offFraction);
            reps.offSpells.push_back(again.meanOff_s);
        }
        for (int k = 0; k < K; ++k)
            reps.logGains[static_cast<std::size_t>(k)].push_back(
                std::log(th.gains[static_cast<std::size_t>(k)]));
    }
    return reps;
}

Theta biasCorrected(const Theta& raw, const Replicates& reps, const std::vector<char>& skip) {
    // The moment fit leans (by about 4 % of the noise on the paper's protocol): the estimate is
    // corrected by the lean the replicates show about it.
    Theta est = raw;
    if (reps.sigmas.empty()) return est;
    est.sigma = std::max(0.0, 2.0 * raw.sigma - meanOf(reps.sigmas));
    est.rate = raw.rate > 0 ? std::max(0.0, 2.0 * raw.rate - meanOf(reps.rates)) : 0.0;
    for (std::size_t k = 0; k < skip.size(); ++k)
        if (!skip[k])
            est.gains[k] = std::clamp(
                std::exp(2.0 * std::log(raw.gains[k]) - meanOf(reps.logGains[k])), 0.05, 20.0);
    return est;
}

void addParameter(SceneFit& fit, const std::string& effect, const std::string& name, double value,
                  double se) {
    fit.parameters.push_back({effect, name, value, se, value - 1.96 * se, value + 1.96 * se});
}

bool chooseNoise(const FitRun& run, const Theta& est, const Replicates& reps, SceneFit& fit) {
    // Listed when the estimate lies more than z standard errors above zero.
    const double se = sd(reps.sigmas);
    const double stat = se > 0 ? est.sigma / se : (est.sigma > 0 ? 1e9 : 0.0);
    const bool listed = stat > run.z;
    fit.choices.push_back({"taxel_noise", listed,
                           "sigma / its standard error against the one-sided normal quantile "
                           "at the level",
                           stat, run.z, true});
    if (listed) addParameter(fit, "taxel_noise", "sigma_counts", est.sigma, se);
    return listed;
}

bool chooseDrift(const FitRun& run, const Theta& est, double targetWander, const Replicates& reps,
                 SceneFit& fit) {
    // Whether the taps' means over nothing wander more than recordings simulated with the fitted
    // scene but no drift do. (A rate over its standard error would test at the boundary:
    // replicates simulated at a small rate read it back as small or as none, and their spread is
    // then no measure of how far from none it lies.)
    Theta none = est;
    none.rate = 0.0;
    const SceneSpec noDrift = run.sceneAt(none);
    std::vector<double> wanders;
    for (int b = 0; b < std::max(run.settings.bootstrapReplicates, 10); ++b)
        wanders.push_back(
            momentsOf(simulateAt(noDrift, run.c.model, run.c.poses,
                                 run.settings.seed + 70000 + static_cast<std::uint64_t>(b)),
                      run.c.masks, run.c.skip)
                .wander);
    const double stat = zAbove(targetWander, wanders);
    const bool listed = est.rate > 0 && stat > run.z;
    fit.choices.push_back(
        {"baseline_drift", listed,
         "the wander of the taps' means over nothing, less its mean over " +
             std::to_string(wanders.size()) +
             " recordings simulated with the fitted scene without drift, over their standard "
             "deviation, against the one-sided normal quantile at the level",
         stat, run.z, true});
    if (listed)
        addParameter(fit, "baseline_drift", "rate_counts_per_sqrt_s", est.rate, sd(reps.rates));
    return listed;
}

namespace {

/// The taxels' common level on the log scale and its variance, from the moment fit's gains.
struct CommonLevel {
    double meanLog = 0.0, meanLogVar = 0.0;
    int df = 0;
    std::vector<double> ses;  ///< per taxel, its log gain's standard error (0 where skipped)
};

CommonLevel commonLevelOf(const Theta& est, const Replicates& reps, const std::vector<char>& skip) {
    CommonLevel l;
    l.ses.assign(skip.size(), 0.0);
    for (std::size_t k = 0; k < skip.size(); ++k) {
        if (skip[k]) continue;
        l.ses[k] = sd(reps.logGains[k]);
        l.meanLog += std::log(est.gains[k]);
        l.meanLogVar += l.ses[k] * l.ses[k];
        ++l.df;
    }
    if (l.df > 0) {
        l.meanLog /= l.df;
        l.meanLogVar /= static_cast<double>(l.df) * l.df;
    }
    return l;
}

/// The gains' common level against the scene's, into `fit`.
void reportPressureScale(const CommonLevel& l, double alpha, SceneFit& fit) {
    const double seCommon = std::sqrt(l.meanLogVar);
    fit.pressureScale = std::exp(l.meanLog);
    fit.pressureScaleLow = std::exp(l.meanLog - 1.96 * seCommon);
    fit.pressureScaleHigh = std::exp(l.meanLog + 1.96 * seCommon);
    fit.pressureScaleDiffers = seCommon > 0
                                   ? std::abs(l.meanLog) / seCommon > stats::normalUpper(alpha / 2)
                                   : l.meanLog != 0.0;
}

}  // namespace

bool chooseGains(const FitRun& run, const Theta& est, const Replicates& reps, SceneFit& fit) {
    // A Wald test of the log gains' spread about their common value (chi-square with one degree
    // of freedom fewer than the live taxels). Their common level is the tapper's as much as the
    // skin's (a deeper stop presses every taxel harder), so it is reported apart.
    const std::vector<char>& skip = run.c.skip;
    const int K = run.taxels();
    const CommonLevel level = commonLevelOf(est, reps, skip);
    // The same statistic on these gains, for the report (skipped taxels have no error).
    std::vector<double> logs(static_cast<std::size_t>(K), 0.0);
    for (std::size_t k = 0; k < logs.size(); ++k) logs[k] = std::log(est.gains[k]);
    fit.momentGainsQ = cochranQ(logs, level.ses);
    // Whether the taxels differ is read from the holds (holdGains()): the moment fit compares
    // whole taps with the scene's stroke, so a stroke that stops deeper or on another schedule
    // would look like gains there. The values and their intervals are the moment fit's.
    const HoldGains held =
        holdGains(holdsOf(run.c.base, *run.c.model, run.c.poses, skip, run.c.maxCounts), K,
                  run.settings.holdReplicates, run.settings.seed + 60000);
    fit.holdTaps = held.taps;
    for (std::size_t k = 0; k < held.logGain.size(); ++k) {
        fit.holdGains.push_back(std::exp(held.logGain[k]));
        fit.holdGainLogSe.push_back(held.se[k]);
    }
    const double threshold =
        held.df > 1 ? stats::chiSquareUpper(held.df - 1, run.settings.alpha) : 0.0;
    const bool listed = held.df > 1 && held.q > threshold;
    fit.choices.push_back({"taxel_gain", listed,
                           "Cochran's Q of the log gains read from the taps' holds (each hold's "
                           "depth fitted to the model at its pose) about their "
                           "inverse-variance weighted mean, errors from resampling the taps, "
                           "against chi-square with one degree of freedom fewer than the "
                           "taxels read, at the level",
                           held.q, threshold, true});
    reportPressureScale(level, run.settings.alpha, fit);
    if (!listed) return false;
    // The gains are one family: 95 % intervals that hold for every live taxel at once
    // (Bonferroni), each from its log's.
    const double zAll = stats::normalUpper(0.025 / std::max(level.df, 1));
    for (int k = 0; k < K; ++k) {
        const std::size_t kk = static_cast<std::size_t>(k);
        if (skip[kk]) continue;
        const double g = est.gains[kk], se = level.ses[kk];
        fit.parameters.push_back({"taxel_gain", "gain_" + std::to_string(k), g, g * se,
                                  g * std::exp(-zAll * se), g * std::exp(zAll * se)});
    }
    return true;
}

}  // namespace activetouch::scenefit
