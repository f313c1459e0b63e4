#pragma once
// The steps of fitScene() (SceneFit.cpp) after the estimators: what the recording is read
// through, the bootstrap about the moment fit, each effect's choice and the goodness of fit
// (FitChoices.cpp, FitReport.cpp). Internal to devices/simulated.
#include "devices/simulated/fit/FitHolds.h"

namespace activetouch::scenefit {

/// The converter as the readings show it: whole counts, and its top where they pile there.
struct Converter {
    bool whole = true;
    double top = 0.0;
    long atTop = 0, belowTop = 0;  ///< readings at the highest value and one count below it
    bool saturates = false;
    double maxCounts = 255.0;  ///< the range the fitted scene takes
};

/// Throws where the recording is too short or its taps are not the scene's shape.
void checkRecording(const SceneSpec& given, const std::vector<TapRecord>& recorded,
                    const SceneFitSettings& settings, int K);

/// Which samples of the noise-free taps `ideal` touch nothing and which press (see Masks).
Masks masksOf(const std::vector<TapRecord>& ideal, int K, double contactThreshold);

/// Dead or stuck taxels into `fit` (deadTaxels, deadReading); the taxels every later step skips.
std::vector<char> readDeadTaxels(const std::vector<TapRecord>& recorded, const Masks& masks, int K,
                                 SceneFit& fit);

Converter readConverter(const std::vector<TapRecord>& recorded, const SceneSpec& base);

/// The intermittent_taxel effect at what `blinking` read.
EffectSpec blinkEffectOf(const Blinking& blinking);

/// What the steps after the moment fit share.
struct FitRun {
    const FitContext& c;
    const SceneFitSettings& settings;
    const std::vector<TapRecord>& idealTaps;
    const Converter& converter;
    const Blinking& blinking;
    double z = 0.0;  ///< the one-sided normal quantile at the level
    int taxels() const { return c.model->taxelCount(); }
    /// The base with `th` in place of the fitted effects.
    SceneSpec sceneAt(const Theta& th) const {
        return sceneWith(c.base, th, c.quantised, c.maxCounts, c.dead, c.deadReading,
                         c.driftTemplate, c.blink);
    }
};

/// The moment fit again on recordings simulated with `fittedAll`, one per replicate.
struct Replicates {
    std::vector<double> sigmas, rates, offFractions, offSpells;
    std::vector<std::vector<double>> logGains;  ///< [taxel][replicate]
};

Replicates bootstrapMoments(const FitRun& run, const SceneSpec& fittedAll);

/// `raw` less the lean the replicates show about it (the bootstrap's bias correction).
Theta biasCorrected(const Theta& raw, const Replicates& reps, const std::vector<char>& skip);

/// An estimate with its standard error and normal 95 % interval into `fit.parameters`.
void addParameter(SceneFit& fit, const std::string& effect, const std::string& name, double value,
                  double se);

/// Each returns whether the effect is listed, its choice (and estimates) into `fit`.
bool chooseNoise(const FitRun& run, const Theta& est, const Replicates& reps, SceneFit& fit);
bool chooseDrift(const FitRun& run, const Theta& est, double targetWander, const Replicates& reps,
                 SceneFit& fit);
bool chooseGains(const FitRun& run, const Theta& est, const Replicates& reps, SceneFit& fit);

/// The pad's memory when the taps' tail calls for it, else nothing.
std::optional<Memory> chooseMemory(const FitRun& run, const SceneSpec& fittedAll, SceneFit& fit);

/// The choices read without a test of their own: dead taxels, the converter, blinking, and the
/// base's effects this fit cannot read.
void reportReadChoices(const FitRun& run, const Replicates& reps, SceneFit& fit);

/// Per taxel, recorded readings against those of `fit.fitted` (twenty simulations into
/// `fit.simulated`).
void measureGoodness(const FitRun& run, SceneFit& fit);
/// The recording against `fit.simulated` on statistics the fit did not use, into
/// `fit.unmodelled` where it lies far outside them.
void lookForUnmodelled(const FitRun& run, const std::vector<TapRecord>& recorded, SceneFit& fit);

}  // namespace activetouch::scenefit
