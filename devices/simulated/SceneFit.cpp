#include "devices/simulated/SceneFit.h"

#include "devices/simulated/fit/FitHolds.h"

namespace activetouch {
using namespace scenefit;

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

bool SceneFit::lists(const std::string& effect) const {
    for (const auto& c : choices)
        if (c.effect == effect) return c.listed;
    return false;
}

std::string fittedSceneJson(const SceneFit& fit) {
    return sceneToJson(fit.fitted).dump(2) + "\n";
}

}  // namespace activetouch
