// The last steps of a scene fit: the pad's memory, the choices read without a test of their
// own, and the goodness of fit per taxel (see fitScene()).
#include "devices/simulated/fit/FitSteps.h"

namespace activetouch::scenefit {

namespace {

/// The memory's standard errors: the fit again on recordings simulated at the estimate.
void addMemoryParameters(const FitRun& run, const SceneSpec& fittedAll, const Memory& memory,
                         SceneFit& fit) {
    const SceneSpec atEstimate = withMemory(fittedAll, memory.fraction, memory.tau);
    const double threshold = run.c.base.tap.contactThreshold;
    std::vector<double> fractions, taus;
    for (int b = 0; b < run.settings.bootstrapReplicates; ++b) {
        const auto replicate =
            simulateAt(atEstimate, run.c.model, run.c.poses,
                       run.settings.seed + 82000 + static_cast<std::uint64_t>(b));
        const Memory again =
            fitMemory(fittedAll, run.c.model, run.c.poses, tailOf(replicate, run.c.skip, threshold),
                      run.c.skip, memory, 3, 2,
                      run.settings.seed + 83000 + 10 * static_cast<std::uint64_t>(b));
        fractions.push_back(again.fraction);
        taus.push_back(again.tau);
    }
    addParameter(fit, "viscoelastic_memory", "fraction", memory.fraction, sd(fractions));
    addParameter(fit, "viscoelastic_memory", "time_constant_s", memory.tau, sd(taus));
}

}  // namespace

std::optional<Memory> chooseMemory(const FitRun& run, const SceneSpec& fittedAll, SceneFit& fit) {
    // Listed where the taps' early tail after a press lies above what recordings simulated with
    // the fitted scene without memory show (the drift test's form), then fitted by simulation,
    // with standard errors from recordings simulated at the estimate.
    const double threshold = run.c.base.tap.contactThreshold;
    const Tail target = tailOf(run.c.poses, run.c.skip, threshold);
    const SceneSpec noMemory = withMemory(fittedAll, 0.0, 0.0);
    std::vector<double> nulls;
    for (int b = 0; b < std::max(run.settings.bootstrapReplicates, 10); ++b)
        nulls.push_back(
            tailOf(simulateAt(noMemory, run.c.model, run.c.poses,
                              run.settings.seed + 80000 + static_cast<std::uint64_t>(b)),
                   run.c.skip, threshold)
                .early);
    const double stat = zAbove(target.early, nulls);
    const bool listed = target.taps >= 10 && stat > run.z;
    fit.choices.push_back(
        {"viscoelastic_memory", listed,
         "what the touching taps' totals still read over their baseline in the three frames "
         "after the press falls, as a share of the press, less its mean over " +
             std::to_string(nulls.size()) +
             " recordings simulated with the fitted scene without memory, over their standard "
             "deviation (" +
             std::to_string(target.taps) +
             " taps with ten frames after the fall), against the one-sided normal quantile "
             "at the level",
         stat, run.z, true});
    if (!listed) return std::nullopt;
    Memory start{0.1, 0.5};
    for (const auto& e : run.c.base.effects)
        if (e.name == "viscoelastic_memory") {
            start.fraction = e.parameters.value("fraction", 0.1);
            start.tau = e.parameters.value("time_constant_s", 0.5);
        }
    const Memory memory = fitMemory(fittedAll, run.c.model, run.c.poses, target, run.c.skip, start,
                                    6, 3, run.settings.seed + 81000);
    addMemoryParameters(run, fittedAll, memory, fit);
    return memory;
}

namespace {

std::string converterReason(const Converter& cv) {
    return std::string("every reading a whole count; ") +
           (cv.saturates ? "the range read from the readings piled at its top (" +
                               std::to_string(cv.atTop) + " at " + numberText(cv.top) + ", " +
                               std::to_string(cv.belowTop) + " one count below)"
                         : "the range not reached (highest reading " + numberText(cv.top) + ", " +
                               std::to_string(cv.atTop) + " there): max_counts " +
                               numberText(cv.maxCounts) + " kept from the base");
}

/// A positive estimate read from few spells: its interval on the log scale.
void addPositive(SceneFit& fit, const char* name, double value, const std::vector<double>& reps) {
    std::vector<double> logs;
    for (double r : reps) logs.push_back(std::log(std::max(r, 1e-6)));
    const double seLog = sd(logs);
    fit.parameters.push_back({"intermittent_taxel", name, value, value * seLog,
                              value * std::exp(-1.96 * seLog), value * std::exp(1.96 * seLog)});
}

}  // namespace

void reportReadChoices(const FitRun& run, const Replicates& reps, SceneFit& fit) {
    const Converter& cv = run.converter;
    const Blinking& blinking = run.blinking;
    fit.choices.push_back({"dead_taxel", !fit.deadTaxels.empty(),
                           "a taxel whose readings in taps where the model presses it over 20 "
                           "counts exceed its readings in taps over nothing by under a twentieth "
                           "of the median taxel's",
                           static_cast<double>(fit.deadTaxels.size()), 1.0, true});
    fit.choices.push_back(
        {"adc_quantisation", cv.whole, converterReason(cv), cv.whole ? 1.0 : 0.0, 1.0, true});
    if (cv.saturates) addParameter(fit, "adc_quantisation", "max_counts", cv.maxCounts, 0.0);
    fit.choices.push_back(
        {"intermittent_taxel", blinking.listed,
         "the most readings of one taxel, deep inside a press that the model and the other "
         "taxels both hold, under a quarter of its median over that press while most of the "
         "frame's pressed taxels are not (a live taxel's noise gives none)",
         static_cast<double>(blinking.mostLow), static_cast<double>(kBlinkReadings), true});
    if (blinking.listed) {
        addPositive(fit, "off_fraction", blinking.offFraction, reps.offFractions);
        addPositive(fit, "mean_off_s", blinking.meanOff_s, reps.offSpells);
        fit.intermittentTaxels = blinking.taxels;
    }
    for (const auto& e : run.c.base.effects)
        if (!estimatedHere(e.name) && e.name != "viscoelastic_memory" &&
            e.name != "contact_latency" && e.name != "stage_error" && e.name != "crosstalk")
            fit.choices.push_back({e.name, true,
                                   "not identifiable from taps by this fit: kept as the base scene "
                                   "lists it",
                                   0.0, 0.0, false});
}

void measureGoodness(const FitRun& run, SceneFit& fit) {
    // Recorded against simulated with the fitted scene, beside what two simulations of it show.
    for (int b = 0; b < 2 * 10; ++b)
        fit.simulated.push_back(
            simulateAt(fit.fitted, run.c.model, run.c.poses,
                       run.settings.seed + 20000 + static_cast<std::uint64_t>(b)));
    const auto& pairs = fit.simulated;
    for (int k = 0; k < run.taxels(); ++k) {
        TaxelFit tf;
        tf.taxel = k;
        const auto rec = readings(run.c.poses, k), sim = readings(fit.simulated.front(), k);
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
}

}  // namespace activetouch::scenefit
