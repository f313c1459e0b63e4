#pragma once
// How far a tap's posterior can be believed (docs/accuracy-vs-time.md, "Calibrated belief").
// Naive Bayes multiplies a tap's 600 samples as if independent, so one tap's posterior is near 1
// whether it is right or not. A calibration maps each tap's log-likelihoods to a belief that
// means what it says, without moving the argmax: the log-likelihoods are scaled by a factor
// s < 1 (a temperature 1/s), and a share e of the belief may be spread evenly over the classes
// (a floor: no single tap rules a class out, as a misread tap can never be ruled out). Both are
// fitted on held-out taps (the negative log-likelihood of their true classes, least), and the
// expected calibration error is measured on held-out taps they were not fitted on, raw and
// calibrated. Three candidates are measured: the temperature alone, the temperature with a
// floor, and the mean log-likelihood per sample (s = 1 / samples); the one with the lowest error
// is kept.
#include <string>
#include <vector>

#include "core/classify/HistogramClassifier.h"
#include "core/tap/Tap.h"

namespace activetouch {

/// One bin of a reliability diagram: taps whose top posterior fell in [lo, hi).
struct ReliabilityBin {
    double lo = 0.0, hi = 0.0;
    int taps = 0;
    double meanConfidence = 0.0, accuracy = 0.0;  ///< 0 when empty
};

/// The expected calibration error over `bins` equal-width bins of confidence: the tap-weighted
/// mean of |accuracy - mean confidence|. `out`, if given, receives the bins. 0 for no taps.
double expectedCalibrationError(const std::vector<double>& confidence,
                                const std::vector<bool>& correct, int bins,
                                std::vector<ReliabilityBin>* out = nullptr);

/// A calibration of one tap's evidence: belief_c = (1 - floor) softmax(scale x ll)_c +
/// floor / C. scale 1 and floor 0 leave the naive-Bayes posterior as it is.
struct BeliefScaling {
    double scale = 1.0;  ///< factor on each log-likelihood, in (0, 1]
    double floor = 0.0;  ///< share of belief spread evenly over the classes, in [0, 1)
};

/// The calibrated log belief of every class from one tap's log-likelihoods, into `out` (count
/// values, normalised: their exponentials sum to 1). The order of the classes is that of the
/// log-likelihoods, so the argmax is theirs. Finite for any log-likelihoods (-inf and NaN rule a
/// class out when the floor is 0, as in SequentialBelief) and any scaling (a scale that is not a
/// positive number counts as 0: every class alike; a floor outside [0, 1) is clamped into it).
void calibratedLogBelief(const double* logLikelihoods, int count, const BeliefScaling& scaling,
                         double* out);

/// The top class's calibrated belief and that class (the argmax of the log-likelihoods).
double calibratedTopBelief(const double* logLikelihoods, int count, const BeliefScaling& scaling,
                           int* top);

/// The top class's posterior (flat prior) of log-likelihoods scaled by `scale`, and that class.
/// Finite for any scale >= 0 and any log-likelihoods, -inf and NaN included (NaN rules a class
/// out, as in SequentialBelief).
double scaledTopPosterior(const double* logLikelihoods, int count, double scale, int* top);

/// The scale in [1e-8, 1] that minimises the mean negative log posterior of the true classes.
double fitLogLikelihoodScale(const std::vector<std::vector<double>>& logLikelihoods,
                             const std::vector<int>& truth);

/// The scale in [1e-8, 1] and floor in [0, 0.99] that together minimise the mean negative log
/// belief of the true classes.
BeliefScaling fitBeliefScaling(const std::vector<std::vector<double>>& logLikelihoods,
                               const std::vector<int>& truth);

/// The expected calibration error a perfectly calibrated belief would still show on these
/// confidences, from the finite number of taps alone: the mean over 400 draws in which each tap
/// is right with exactly its confidence (a fixed pseudo-random sequence, so the same for the
/// same confidences). An error near this one is as small as the taps can show.
double expectedCalibrationErrorIfCalibrated(const std::vector<double>& confidence, int bins);

struct BeliefCalibration {
    bool measured = false;
    /// "temperature fitted on held-out taps", "temperature and floor fitted on held-out taps"
    /// or "mean per sample"
    std::string method;
    BeliefScaling scaling;  ///< the kept calibration of one tap's belief
    /// The calibration of evidence accumulated over repeated taps of one class: taps at one
    /// place repeat much of their misreading, so their evidence is worth less than independent
    /// taps' would be. The factor is fitted, as the single tap's, on the held-out taps, here on
    /// the running sums of each class's held-out taps in turn (every prefix of each class's
    /// sequence); sequential decisions use it.
    BeliefScaling sequential;
    int sequencePrefixes = 0;  ///< how many running sums it was fitted on
    double fittedScale = 1.0, perSampleScale = 1.0;
    BeliefScaling fittedWithFloor;
    double eceRaw = 0.0, eceCalibrated = 0.0;  ///< on the evaluation taps
    /// Each candidate's error, on the same taps.
    double eceFitted = 0.0, eceFittedWithFloor = 0.0, ecePerSample = 0.0;
    /// What a perfectly calibrated belief would show on the kept confidences (the sampling
    /// floor of the measurement; see expectedCalibrationErrorIfCalibrated).
    double eceIfCalibrated = 0.0;
    double accuracy = 0.0;                        ///< single-tap class accuracy there
    int fitTaps = 0, evaluationTaps = 0;          ///< both every held-out tap (two folds)
    std::vector<ReliabilityBin> raw, calibrated;  ///< 10 bins each
};

/// Calibrates on held-out taps (not used for training), cross-fitted over two folds (the even-
/// and odd-numbered taps): each tap's calibrated confidence uses the scaling fitted on the other
/// fold, so every error is measured on taps its scaling never saw; the scaling kept is fitted on
/// them all. The per-sample mean's factor is 1 / (samples x taxels) of the taps. Not
/// measured with fewer than 4 taps.
BeliefCalibration calibrateBelief(const HistogramClassifier& classifier,
                                  const std::vector<const Tap*>& heldOut,
                                  const std::vector<int>& truth);

}  // namespace activetouch
