#pragma once
// The parts of a scene fit (SceneFit.h), one estimator a file: moments (noise, drift, gains),
// blinking, the holds (gains, stage error, crosstalk), latency and memory. Internal to
// devices/simulated: what the estimators share, declared once.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/common/InputError.h"
#include "core/common/NumberText.h"
#include "core/run/ExperimentRun.h"
#include "core/stats/Distributions.h"
#include "core/stats/SampleTests.h"
#include "devices/simulated/SceneFit.h"
#include "devices/simulated/SimulatedWorld.h"

namespace activetouch::scenefit {

using stats::cochranQ;
using stats::ksDistance;
using stats::wasserstein;

/// The effects this fit estimates from taps; every other effect is kept as the base lists it.
inline const char* const kEstimated[] = {"taxel_noise", "baseline_drift",   "taxel_gain",
                                         "dead_taxel",  "adc_quantisation", "intermittent_taxel"};

bool estimatedHere(const std::string& name);

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

std::vector<double> frameTotals(const Tap& tap, const std::vector<char>& skip);

/// The level of a press in frame totals `total` whose least and most are `lowest` and `highest`:
/// the median of the totals above half the range, most of which are the hold's (a pad with
/// memory reads above it for a frame after release).

double pressLevel(const std::vector<double>& total, double lowest, double highest);

/// Per frame of `tap`, whether its total over the live taxels lies within `margin` counts above
/// the tap's quiet level (the tenth percentile of its frames' totals). A stroke on another
/// schedule than the model's (a real tapper's, or one the host held up) presses where the model
/// does not; this keeps such frames out of what is read as over nothing, alike in recorded and
/// simulated taps, and noise alone does not reach it.

std::vector<char> quietFrames(const Tap& tap, const std::vector<char>& skip, double margin);

inline constexpr double kPressed = 20.0;

/// The widest coupling the crosstalk effect takes, either way (read values may fall below zero).
inline constexpr double kMaxCoupling = 0.5;

/// The crosstalk's neighbourhood where the base scene gives none (the effect's default), mm.
inline constexpr double kDefaultCouplingRadius_mm = 4.5;

/// A converter's range shows as at least this many readings at the highest value, and this many
/// times as many as one count below it.
inline constexpr long kPileReadings = 20;

inline constexpr long kPileRatio = 4;

inline constexpr int kMargin = 4;

Moments momentsOf(const std::vector<TapRecord>& taps, const Masks& masks,
                  const std::vector<char>& skip);

/// The scene with the fitted effects in place of the base's own of those names.

SceneSpec sceneWith(const SceneSpec& base, const Theta& th, bool quantised, double maxCounts,
                    const std::vector<int>& dead, double deadReading,
                    const EffectSpec* driftTemplate, const EffectSpec* blink);

/// Taps simulated with `scene` at the poses of `at`; with `strokes`, each stopping where its
/// recorded namesake did where that was recorded (a tap the reflex ended, with its stop depth).

std::vector<TapRecord> simulateAt(const SceneSpec& scene,
                                  const std::shared_ptr<const FingertipContactModel>& model,
                                  const std::vector<TapRecord>& at, std::uint64_t seed,
                                  bool strokes = false);

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

Theta fitMoments(const FitContext& c, const Moments& target, std::uint64_t seed);

/// Readings deep inside a press (the model presses the taxel over kBlinkDeep counts from
/// kMargin samples before to kMargin after) that fall under a quarter of the taxel's median over
/// that stretch of the tap, where that median is over kPressed; a frame in which most of the
/// pressed taxels fall together is a lost frame, not a blink, and is left out.
inline constexpr double kBlinkDeep = 30.0;

/// A taxel is taken to blink from this many such readings: noise on a live taxel gives none
/// (a reading a quarter of a median over 20 counts lies over ten noise deviations below it).
inline constexpr long kBlinkReadings = 5;

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
                    const std::vector<char>& skip, const std::vector<int>& only);

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
                      const std::vector<int>& taxels = {});

std::vector<double> readings(const std::vector<TapRecord>& taps, int k);

/// The mean of `v` (non-empty).

double meanOf(const std::vector<double>& v);

double sd(const std::vector<double>& v);

/// How far `value` lies above the mean of `nulls` (recordings simulated without an effect), in
/// their standard deviations; 1e9 above a mean they do not spread about, 0 at or below it.

double zAbove(double value, const std::vector<double>& nulls);

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

inline constexpr int kTailFrames = 10;

Tail tailOf(const std::vector<TapRecord>& taps, const std::vector<char>& skip,
            double contactThreshold);

/// `scene` with effect `name` at `parameters` in place of its own, or without it where
/// `parameters` is null.

SceneSpec withEffect(const SceneSpec& scene, const std::string& name, const Json& parameters);

/// `scene` with the pad's memory at (fraction, time constant), or without it at fraction 0.

SceneSpec withMemory(const SceneSpec& scene, double fraction, double tau);

/// `scene` with the reflex's latency at `latency_s`, or without one at 0.

SceneSpec withLatency(const SceneSpec& scene, double latency_s);

/// A latency is read from this many taps the reflex ended with their stop depths recorded.
inline constexpr int kLagTaps = 10;

/// Recordings simulated per round of the latency's correction.
inline constexpr int kLagSimulations = 10;

/// The longest latency the effect takes.
inline constexpr double kMaxLatency_s = 0.5;

/// Where the noise-free model at each tap's pose reaches the reflex's threshold within the
/// stroke, mm below the object's top (NaN where it does not).

std::vector<double> crossingsOf(const SceneSpec& scene, const FingertipContactModel& model,
                                const std::vector<TapRecord>& taps);

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
                  const SceneSpec& scene);

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
                 std::uint64_t seed);

SceneSpec readLatency(const SceneSpec& given,
                      const std::shared_ptr<const FingertipContactModel>& model,
                      const std::vector<TapRecord>& recorded, const SceneFitSettings& settings,
                      double z, SceneFit& fit);

/// Crosstalk (see the comment inside): its choice and estimate into `fit`, and `base` with the
/// coupling read (or without one).

}  // namespace activetouch::scenefit
