#pragma once
// Fitting a scene to recorded taps (activetouch-cli calibrate; docs/calibration.md). The taps'
// poses are known, so the simulated rig can take the same taps: each estimate is the parameter
// value at which taps simulated at the recorded poses show the recorded statistics (the method
// of simulated moments), its uncertainty the spread of the estimates over recordings simulated
// with the fitted scene (a parametric bootstrap), and an effect is listed only where a test at
// the stated level says the taps call for it.
#include <string>
#include <vector>

#include "core/experiment/Experiment.h"
#include "core/scene/Scene.h"
#include "core/tap/Tap.h"
#include "core/validation/OfflineValidation.h"

namespace activetouch {

struct SceneFitSettings {
    int bootstrapReplicates = 20;  ///< recordings simulated at the estimate, for its uncertainty
    int iterations = 12;           ///< moment-matching rounds per fit
    int simulationsPerRound = 3;   ///< simulated recordings whose moments each round matches
    int holdReplicates = 200;      ///< resamplings of the taps' holds, for the gains test
    /// An effect is listed when its test statistic's p-value under "absent" is below this.
    double alpha = 0.001;
    std::uint64_t seed = 1;  ///< of the simulations the fit runs (common to every round)
    /// The recording's name, for what the fit refuses about the recorded taps.
    std::string recording = "the recording";
};

struct FittedParameter {
    std::string effect, parameter;
    double value = 0.0;
    double standardError = 0.0;  ///< over the bootstrap replicates
    /// 95 % interval: value -/+ 1.96 standard errors; for the gains, a log interval that holds
    /// for every taxel at once (Bonferroni over the live taxels)
    double low = 0.0, high = 0.0;
};

/// Whether the taps call for an effect, and why.
struct EffectChoice {
    std::string effect;
    bool listed = false;
    std::string test;  ///< how it was decided, in a sentence, with its statistic
    double statistic = 0.0, threshold = 0.0;
    bool estimated = true;  ///< false: not identifiable from taps by this fit; kept from the base
};

/// How well the fitted scene reproduces the taps: per taxel, the Kolmogorov-Smirnov distance
/// between the recorded readings and readings simulated with the fitted scene at the same poses,
/// against the distance two simulations of that scene show at the 95th percentile (a match is a
/// distance at or under it).
struct TaxelFit {
    int taxel = 0;
    double ks = 0.0, ksMatch = 0.0;
    double wasserstein = 0.0;  ///< counts
    bool matches = false;
};

/// Something the recording shows that the fitted scene does not produce, on a statistic the fit
/// did not use (devices/simulated/fit/FitUnmodelled.cpp): the recording's value against twenty
/// recordings simulated with the fitted scene.
struct Unmodelled {
    std::string statistic;  ///< "readings piled at one level", ...
    double recorded = 0.0, simulatedMean = 0.0, simulatedLeast = 0.0, simulatedLargest = 0.0;
    double z = 0.0;            ///< (recorded - simulated mean) / their standard deviation
    std::string explanation;  ///< what it suggests the scene lacks
};

struct SceneFit {
    SceneSpec fitted;  ///< the base scene with the fitted effects listed, the others as in the base
    std::vector<FittedParameter> parameters;
    std::vector<EffectChoice> choices;
    std::vector<TaxelFit> taxels;
    /// What the recording shows that the fitted scene does not (empty where nothing does).
    std::vector<Unmodelled> unmodelled;
    /// Whether the fitted scene lists `effect` (its choice says so).
    bool lists(const std::string& effect) const;
    /// The taps' pressure level against the fitted scene's, over every live taxel: a tapper that
    /// stops at another depth (latency, stroke) or a skin more sensitive throughout. Not fitted;
    /// said when it differs at the level.
    double pressureScale = 1.0, pressureScaleLow = 1.0, pressureScaleHigh = 1.0;
    bool pressureScaleDiffers = false;
    /// What the gains test read (taxel_gain's choice): each taxel's gain relative to the others
    /// as the taps' holds show it (NaN where too few holds press it or it is dead), its standard
    /// error on the log scale (0 where not tested), the touching taps whose hold was read, and
    /// the same statistic on the moment fit's gains, which a stroke on another schedule or to
    /// another depth than the scene's moves.
    std::vector<double> holdGains, holdGainLogSe;
    int holdTaps = 0;
    double momentGainsQ = 0.0;
    std::vector<int> deadTaxels;
    double deadReading = 0.0;
    std::vector<int> intermittentTaxels;  ///< taxels that blink, where the taps show it
    int taps = 0;
    long nothingSamples = 0;  ///< samples over nothing the noise and drift were read from
    /// Twenty recordings simulated with the fitted scene at the recorded poses (the first is
    /// compared with the recording; pairs of the others say what a match is).
    std::vector<std::vector<TapRecord>> simulated;
};

/// Fits `base` (its object, fingertip, tap and stage as mounted) to `recorded` taps, taken at
/// their poses. Throws InputError (naming `settings.recording`) if the taps cannot be fitted:
/// fewer than 20, of another shape than the scene's tap, none over nothing.
SceneFit fitScene(const SceneSpec& base, const std::vector<TapRecord>& recorded,
                  const SceneFitSettings& settings = {});

/// Figure 6 recorded beside Figure 6 simulated: the experiment's validation on the recorded taps,
/// and on each of the fit's simulated recordings with the same labels (one recording's validation
/// alone varies by several degrees), with their mean, least and largest.
struct Figure6Comparison {
    ValidationResult recorded;
    std::vector<ValidationResult> simulated;
    double angleMean = 0, angleLeast = 0, angleLargest = 0;
    double positionMean = 0, positionLeast = 0, positionLargest = 0;
    bool recordedInsideRange = false;  ///< both recorded errors within the simulated least..largest
    std::vector<CollectedTap> firstSimulated;  ///< the first simulated recording, labelled
};
Figure6Comparison compareFigure6(const ExperimentSpec& spec, const std::vector<CollectedTap>& taps,
                                 const SceneFit& fit);

/// The fitted scene as a scene file's JSON, with the fit's estimates and choices under
/// "calibration".
std::string fittedSceneJson(const SceneFit& fit);

}  // namespace activetouch
