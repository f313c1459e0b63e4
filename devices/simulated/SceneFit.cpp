#include "devices/simulated/SceneFit.h"

#include "devices/simulated/fit/FitSteps.h"

namespace activetouch {
using namespace scenefit;

SceneFit fitScene(const SceneSpec& given, const std::vector<TapRecord>& recorded,
                  const SceneFitSettings& settings) {
    auto model = std::make_shared<const FingertipContactModel>(given.fingertip);
    const int K = model->taxelCount();
    checkRecording(given, recorded, settings, K);
    SceneFit fit;
    const double z = stats::normalUpper(settings.alpha);

    // The reflex's latency first: every simulation below then presses, on average, as deep as
    // the recorded taps did.
    SceneSpec base = readLatency(given, model, recorded, settings, z, fit);

    // Samples over nothing: the noise-free model at each recorded pose touches nothing there.
    SceneSpec ideal = base;
    ideal.effects.clear();
    const std::vector<TapRecord> idealTaps = simulateAt(ideal, model, recorded, 1);
    const Masks masks = masksOf(idealTaps, K, base.tap.contactThreshold);
    fit.taps = static_cast<int>(recorded.size());
    const std::vector<char> skip = readDeadTaxels(recorded, masks, K, fit);
    const Converter converter = readConverter(recorded, base);

    // Blinking taxels, read before the gains so that every simulation the gains are fitted to
    // blinks alike.
    const Blinking blinking = readBlinking(base, model, recorded, idealTaps, skip,
                                           1.0 / base.tap.sampleRate_hz, settings.seed + 30000);
    const EffectSpec blinkEffect = blinkEffectOf(blinking);

    // Crosstalk, before the noise, drift and gains: a coupling left out is taken for gains.
    base = readCrosstalk(given, base, model, recorded, skip, converter.maxCounts, settings, z, fit);

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
    const FitContext c{base,
                       model,
                       masks,
                       recorded,
                       converter.whole,
                       converter.maxCounts,
                       fit.deadTaxels,
                       fit.deadReading,
                       driftTemplate,
                       blinking.listed ? &blinkEffect : nullptr,
                       skip,
                       settings.iterations,
                       settings.simulationsPerRound};
    const FitRun run{c, settings, idealTaps, converter, blinking, z};
    const Theta raw = fitMoments(c, target, settings.seed);
    const SceneSpec fittedAll = run.sceneAt(raw);

    // Uncertainty: the same fit on recordings simulated with the estimate.
    const Replicates reps = bootstrapMoments(run, fittedAll);
    const Theta est = biasCorrected(raw, reps, skip);
    Theta chosen = est;
    if (!chooseNoise(run, est, reps, fit)) chosen.sigma = 0.0;
    if (!chooseDrift(run, est, target.wander, reps, fit)) chosen.rate = 0.0;
    if (!chooseGains(run, est, reps, fit)) std::fill(chosen.gains.begin(), chosen.gains.end(), 1.0);
    const std::optional<Memory> memory = chooseMemory(run, fittedAll, fit);
    reportReadChoices(run, reps, fit);

    fit.fitted = withMemory(run.sceneAt(chosen), memory ? memory->fraction : 0.0,
                            memory ? memory->tau : 0.0);
    // The stage's error last, against the scene as fitted.
    if (const auto stageSigma = readStageError(given, base, model, recorded, skip,
                                               converter.maxCounts, settings, z, fit))
        fit.fitted = withEffect(fit.fitted, "stage_error", Json{{"sigma_mm", *stageSigma}});
    measureGoodness(run, fit);
    lookForUnmodelled(run, recorded, fit);
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
