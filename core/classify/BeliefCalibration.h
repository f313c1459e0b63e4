#pragma once
// How far a tap's posterior can be believed (docs/accuracy-vs-time.md, "Calibrated belief").
// Naive Bayes multiplies a tap's 600 samples as if independent, so one tap's posterior is near 1
// whether it is right or not. Scaling each tap's log-likelihoods by a factor s < 1 (a
// temperature 1/s) leaves the argmax where it is and makes the confidence mean something: the
// factor is fitted on held-out taps (the negative log-likelihood of their true classes, least),
// and the expected calibration error measured on held-out taps it was not fitted on, raw and
// scaled. The mean
// log-likelihood per sample (s = 1 / samples) is measured beside it; the one with the lower
// error is kept.
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

/// The top class's posterior (flat prior) of log-likelihoods scaled by `scale`, and that class.
/// Finite for any scale >= 0 and any log-likelihoods, -inf and NaN included (NaN rules a class
/// out, as in SequentialBelief).
double scaledTopPosterior(const double* logLikelihoods, int count, double scale, int* top);

/// The scale in [1e-8, 1] that minimises the mean negative log posterior of the true classes.
double fitLogLikelihoodScale(const std::vector<std::vector<double>>& logLikelihoods,
                             const std::vector<int>& truth);

struct BeliefCalibration {
    bool measured = false;
    std::string method;  ///< "temperature fitted on held-out taps" or "mean per sample"
    double scale = 1.0;  ///< the kept factor on each tap's log-likelihoods
    double fittedScale = 1.0, perSampleScale = 1.0;
    double eceRaw = 0.0, eceCalibrated = 0.0;     ///< on the evaluation taps
    double eceFitted = 0.0, ecePerSample = 0.0;   ///< each candidate's, on the same taps
    double accuracy = 0.0;                        ///< single-tap class accuracy there
    int fitTaps = 0, evaluationTaps = 0;          ///< both every held-out tap (two folds)
    std::vector<ReliabilityBin> raw, calibrated;  ///< 10 bins each
};

/// Calibrates on held-out taps (not used for training), cross-fitted over two folds (the even-
/// and odd-numbered taps): each tap's calibrated confidence uses the factor fitted on the other
/// fold, so every error is measured on taps its factor never saw; the factor kept (`scale`) is
/// fitted on them all. The per-sample mean's factor is 1 / (samples x taxels) of the taps. Not
/// measured with fewer than 4 taps.
BeliefCalibration calibrateBelief(const HistogramClassifier& classifier,
                                  const std::vector<const Tap*>& heldOut,
                                  const std::vector<int>& truth);

}  // namespace activetouch
