#include "core/classify/BeliefCalibration.h"

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <tuple>

namespace activetouch {

namespace {

/// A confidence as the reliability diagram reads it: clamped into [0, 1], 0 where not finite.
double binned(double confidence) {
    return std::isfinite(confidence) ? std::clamp(confidence, 0.0, 1.0) : 0.0;
}

/// The bin of `c` (binned()) among `bins` equal bins, 1 in the last.
std::size_t binOf(double c, std::size_t bins) {
    return std::min(bins - 1, static_cast<std::size_t>(c * static_cast<double>(bins)));
}

/// The tap-weighted mean gap between accuracy and confidence over bins whose means are set.
double eceOf(const std::vector<ReliabilityBin>& b) {
    double ece = 0.0;
    int total = 0;
    for (const auto& bin : b) {
        if (bin.taps == 0) continue;
        ece += bin.taps * std::abs(bin.accuracy - bin.meanConfidence);
        total += bin.taps;
    }
    return total > 0 ? ece / total : 0.0;
}

}  // namespace

double expectedCalibrationError(const std::vector<double>& confidence,
                                const std::vector<bool>& correct, int bins,
                                std::vector<ReliabilityBin>* out) {
    std::vector<ReliabilityBin> b(static_cast<std::size_t>(std::max(1, bins)));
    const double width = 1.0 / static_cast<double>(b.size());
    for (std::size_t i = 0; i < b.size(); ++i) {
        b[i].lo = width * static_cast<double>(i);
        b[i].hi = i + 1 == b.size() ? 1.0 : width * static_cast<double>(i + 1);
    }
    for (std::size_t t = 0; t < confidence.size() && t < correct.size(); ++t) {
        const double c = binned(confidence[t]);
        ReliabilityBin& bin = b[binOf(c, b.size())];
        ++bin.taps;
        bin.meanConfidence += c;
        bin.accuracy += correct[t] ? 1.0 : 0.0;
    }
    for (auto& bin : b) {
        if (bin.taps == 0) continue;
        bin.meanConfidence /= bin.taps;
        bin.accuracy /= bin.taps;
    }
    if (out) *out = b;
    return eceOf(b);
}

void calibratedLogBelief(const double* ll, int count, const BeliefScaling& scaling, double* out) {
    if (count < 1) return;
    const double s = std::isfinite(scaling.scale) && scaling.scale > 0.0 ? scaling.scale : 0.0;
    const double e = std::isfinite(scaling.floor) ? std::clamp(scaling.floor, 0.0, 0.999999) : 0.0;
    const double inf = std::numeric_limits<double>::infinity();
    for (int c = 0; c < count; ++c) {
        double x = ll[c];
        if (std::isnan(x)) x = -inf;
        if (x == inf) x = std::numeric_limits<double>::max();
        out[c] = s == 0.0 ? (std::isfinite(x) ? 0.0 : x) : s * x;
    }
    double norm = logSumExp(out, count);
    if (!std::isfinite(norm)) {
        // Nothing tells the classes apart (every class ruled out): an even belief.
        for (int c = 0; c < count; ++c) out[c] = -std::log(static_cast<double>(count));
        return;
    }
    for (int c = 0; c < count; ++c) out[c] -= norm;
    if (e == 0.0) return;
    // log((1 - e) p + e / C), as a log-sum of two terms so that tiny p stay exact.
    const double a = std::log1p(-e), b = std::log(e / static_cast<double>(count));
    for (int c = 0; c < count; ++c) {
        const double x = a + out[c];
        const double hi = std::max(x, b), lo = std::min(x, b);
        out[c] = hi + std::log1p(std::exp(lo - hi));
    }
}

double calibratedTopBelief(const double* ll, int count, const BeliefScaling& scaling, int* top) {
    thread_local std::vector<double> v;
    v.resize(static_cast<std::size_t>(std::max(1, count)));
    calibratedLogBelief(ll, count, scaling, v.data());
    // The top class is the log-likelihoods' own argmax (the calibration is monotone; NaN never
    // wins), found on them so that rounding in the scaling cannot reorder near-ties.
    const int best = argmaxLowestIndex(ll, count);
    if (top) *top = best;
    return std::clamp(std::exp(v[static_cast<std::size_t>(best)]), 0.0, 1.0);
}

double scaledTopPosterior(const double* ll, int count, double scale, int* top) {
    return calibratedTopBelief(ll, count, {scale, 0.0}, top);
}

namespace {

// The least of f over [a, b], to within about 2^-bits of its place (Brent's method: golden-section
// steps where parabolic ones would not shrink the bracket), as Boost.Math finds it.
template <class F>
double leastOf(F f, double a, double b, int bits) {
    std::uintmax_t evaluations = 200;
    return boost::math::tools::brent_find_minima(f, a, b, bits, evaluations).first;
}

// The held-out taps made ready for many scales: each tap's log-likelihoods less its largest (NaN
// ruling a class out), and its true class's. Under a scale s > 0 the true class's log posterior
// is then s * gap[true] - log sum exp(s * gap), with nothing to copy or search for per scale. A
// tap without a finite largest value (every class ruled out, or one at +infinity) has the same
// log posterior under every such scale: worked out once.
struct ScaledTaps {
    std::vector<double> gaps;   // tap by tap, classes each
    std::vector<double> truth;  // the true class's gap
    std::vector<char> plain;    // a tap without a finite largest value
    std::vector<double> plainValue;
    int classes = 0;

    ScaledTaps(const std::vector<std::vector<double>>& lls, const std::vector<int>& t)
        : classes(lls.empty() ? 0 : static_cast<int>(lls[0].size())) {
        const double inf = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < lls.size(); ++k) {
            std::vector<double> v = lls[k];
            for (double& x : v) x = std::isnan(x) ? -inf : x;
            const double top = *std::max_element(v.begin(), v.end());
            const double own = v[static_cast<std::size_t>(t[k])];
            plain.push_back(std::isfinite(top) ? 0 : 1);
            plainValue.push_back(std::isfinite(top) ? 0.0 : own - logSumExp(v.data(), classes));
            for (double x : v) gaps.push_back(std::isfinite(top) ? x - top : -inf);
            truth.push_back(std::isfinite(top) ? own - top : -inf);
        }
    }

    // Each tap's log posterior of its true class under `scale` (> 0), into `out`.
    void logPosteriors(double scale, std::vector<double>& out) const {
        out.resize(truth.size());
        for (std::size_t k = 0; k < truth.size(); ++k)
            out[k] =
                plain[k]
                    ? plainValue[k]
                    : scale * truth[k] -
                          std::log(sumExpScaled(gaps.data() + k * static_cast<std::size_t>(classes),
                                                classes, scale));
    }
};

double meanNegativeLogPosterior(const ScaledTaps& taps, double scale) {
    thread_local std::vector<double> lp;
    taps.logPosteriors(scale, lp);
    double sum = 0.0;
    for (double x : lp) sum -= x;
    return lp.empty() ? 0.0 : sum / static_cast<double>(lp.size());
}

}  // namespace

double fitLogLikelihoodScale(const std::vector<std::vector<double>>& ll,
                             const std::vector<int>& truth) {
    // Over log10(scale) in [-8, 0]: the held-out negative log-likelihood of a temperature is
    // unimodal in it.
    const ScaledTaps taps(ll, truth);
    return std::pow(
        10.0, leastOf([&](double x) { return meanNegativeLogPosterior(taps, std::pow(10.0, x)); },
                      -8.0, 0.0, 20));
}

BeliefScaling fitBeliefScaling(const std::vector<std::vector<double>>& ll,
                               const std::vector<int>& truth) {
    BeliefScaling best;
    if (ll.empty()) return best;
    // For a given scale, the true classes' softmax probabilities; the floor's negative
    // log-likelihood, -mean log((1 - e) p + e / C), is convex in e.
    std::vector<double> p;
    const ScaledTaps taps(ll, truth);
    auto floorFor = [&](double scale, double* cost) {
        taps.logPosteriors(scale, p);
        for (double& x : p) x = std::isfinite(x) ? std::exp(x) : 0.0;
        const double evenShare = 1.0 / static_cast<double>(ll.front().size());
        auto nll = [&](double e) {
            double sum = 0.0;
            for (double q : p) sum -= std::log((1.0 - e) * q + e * evenShare);
            return sum / static_cast<double>(p.size());
        };
        const double e = leastOf(nll, 0.0, 0.99, 17);
        // The search's ends are not probed: keep no floor where none does better.
        const double withFloor = nll(e), without = nll(0.0);
        *cost = std::min(withFloor, without);
        return withFloor < without ? e : 0.0;
    };
    const double logScale = leastOf(
        [&](double x) {
            double cost = 0.0;
            floorFor(std::pow(10.0, x), &cost);
            return cost;
        },
        -8.0, 0.0, 14);
    best.scale = std::pow(10.0, logScale);
    double cost = 0.0;
    best.floor = floorFor(best.scale, &cost);
    return best;
}

double expectedCalibrationErrorIfCalibrated(const std::vector<double>& confidence, int bins) {
    if (confidence.empty()) return 0.0;
    // A fixed 64-bit linear congruential sequence (Knuth's MMIX constants), its top 53 bits as
    // a uniform draw: the same figure on every platform.
    std::uint64_t state = 0x9E3779B97F4A7C15ULL;
    auto uniform = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state >> 11) * 0x1p-53;
    };
    // What expectedCalibrationError() works out from the confidences alone, once: each tap's
    // bin, each bin's taps and mean confidence. A draw then only counts each bin's right taps.
    std::vector<ReliabilityBin> b;
    expectedCalibrationError(confidence, std::vector<bool>(confidence.size(), false), bins, &b);
    std::vector<std::size_t> bin(confidence.size());
    for (std::size_t t = 0; t < confidence.size(); ++t)
        bin[t] = binOf(binned(confidence[t]), b.size());
    constexpr int kDraws = 400;
    std::vector<double> right(b.size());
    double sum = 0.0;
    for (int d = 0; d < kDraws; ++d) {
        std::fill(right.begin(), right.end(), 0.0);
        for (std::size_t t = 0; t < confidence.size(); ++t)
            right[bin[t]] += uniform() < std::clamp(confidence[t], 0.0, 1.0) ? 1.0 : 0.0;
        for (std::size_t i = 0; i < b.size(); ++i)
            if (b[i].taps > 0) b[i].accuracy = right[i] / b[i].taps;
        sum += eceOf(b);
    }
    return sum / kDraws;
}

namespace {

/// The held-out taps' log-likelihoods in two folds (even- and odd-numbered taps).
struct Folds {
    std::vector<std::vector<double>> ll[2];
    std::vector<int> truth[2];
    int samples = 0;  ///< the most readings in one tap
};

Folds foldsOf(const HistogramClassifier& classifier, const std::vector<const Tap*>& heldOut,
              const std::vector<int>& truth) {
    Folds f;
    for (std::size_t t = 0; t < heldOut.size(); ++t) {
        std::vector<double> v(static_cast<std::size_t>(classifier.classCount()));
        classifier.logLikelihoods(*heldOut[t], v.data());
        f.samples = std::max(f.samples, heldOut[t]->sampleCount() * heldOut[t]->taxels);
        f.ll[t % 2].push_back(std::move(v));
        f.truth[t % 2].push_back(truth[t]);
    }
    return f;
}

/// The expected calibration error with each tap's confidence under scaling[its fold].
double eceUnder(const Folds& folds, int C, const BeliefScaling (&scaling)[2],
                std::vector<ReliabilityBin>* bins, std::vector<double>* confidenceOut = nullptr) {
    std::vector<double> confidence;
    std::vector<bool> correct;
    for (int f = 0; f < 2; ++f)
        for (std::size_t t = 0; t < folds.ll[f].size(); ++t) {
            int top = 0;
            confidence.push_back(calibratedTopBelief(folds.ll[f][t].data(), C, scaling[f], &top));
            correct.push_back(top == folds.truth[f][t]);
        }
    if (confidenceOut) *confidenceOut = confidence;
    return expectedCalibrationError(confidence, correct, 10, bins);
}

/// A scaling to choose from: fitted per fold on the other fold (to measure) and on every tap
/// (to keep).
struct Candidate {
    const char* method;
    BeliefScaling kept;
    BeliefScaling perFold[2];
    double ece = 0.0;
    std::vector<ReliabilityBin> bins;
    std::vector<double> confidence;
};

/// The sequential factor: fitted on the running sums of each class's held-out taps, in the
/// order they were taken; and how many sums it was fitted on.
std::pair<BeliefScaling, int> sequentialScaling(const Folds& folds, const std::vector<int>& truth,
                                                int C) {
    std::vector<std::vector<double>> sums;
    std::vector<int> sumTruth;
    std::vector<std::size_t> lastOfClass(static_cast<std::size_t>(C), SIZE_MAX);
    for (std::size_t t = 0; t < truth.size(); ++t) {
        const auto& v = folds.ll[t % 2][t / 2];
        auto& last = lastOfClass[static_cast<std::size_t>(truth[t])];
        std::vector<double> sum = v;
        if (last != SIZE_MAX)
            for (std::size_t c = 0; c < sum.size(); ++c) sum[c] += sums[last][c];
        last = sums.size();
        sums.push_back(std::move(sum));
        sumTruth.push_back(truth[t]);
    }
    return {{fitLogLikelihoodScale(sums, sumTruth), 0.0}, static_cast<int>(sums.size())};
}

}  // namespace

BeliefCalibration calibrateBelief(const HistogramClassifier& classifier,
                                  const std::vector<const Tap*>& heldOut,
                                  const std::vector<int>& truth) {
    BeliefCalibration r;
    if (heldOut.size() < 4 || heldOut.size() != truth.size() || !classifier.trained()) return r;
    const int C = classifier.classCount();
    // Two folds of the held-out taps: each tap's calibrated confidence comes from the scaling
    // fitted on the other fold, so every error is measured on taps the scaling never saw; the
    // scaling kept for use is fitted on them all.
    const Folds folds = foldsOf(classifier, heldOut, truth);
    const auto& ll = folds.ll;
    const auto& fold = folds.truth;
    std::vector<std::vector<double>> all = ll[0];
    all.insert(all.end(), ll[1].begin(), ll[1].end());
    std::vector<int> allTruth = fold[0];
    allTruth.insert(allTruth.end(), fold[1].begin(), fold[1].end());
    r.fittedScale = fitLogLikelihoodScale(all, allTruth);
    r.fittedWithFloor = fitBeliefScaling(all, allTruth);
    r.perSampleScale = 1.0 / std::max(1, folds.samples);
    const BeliefScaling perSample{r.perSampleScale, 0.0};
    Candidate candidates[3] = {
        {"temperature fitted on held-out taps",
         {r.fittedScale, 0.0},
         {{fitLogLikelihoodScale(ll[1], fold[1]), 0.0},
          {fitLogLikelihoodScale(ll[0], fold[0]), 0.0}},
         0.0,
         {},
         {}},
        {"temperature and floor fitted on held-out taps",
         r.fittedWithFloor,
         {fitBeliefScaling(ll[1], fold[1]), fitBeliefScaling(ll[0], fold[0])},
         0.0,
         {},
         {}},
        {"mean per sample", perSample, {perSample, perSample}, 0.0, {}, {}}};
    for (Candidate& c : candidates) c.ece = eceUnder(folds, C, c.perFold, &c.bins, &c.confidence);
    const BeliefScaling raw[2] = {};
    r.eceRaw = eceUnder(folds, C, raw, &r.raw);
    r.eceFitted = candidates[0].ece;
    r.eceFittedWithFloor = candidates[1].ece;
    r.ecePerSample = candidates[2].ece;
    const Candidate* kept = &candidates[0];
    // The simpler candidate unless another does measurably better (a floor fitted at 0 is the
    // temperature alone).
    for (const Candidate& c : candidates)
        if (c.ece < kept->ece - 1e-9) kept = &c;
    r.method = kept->method;
    r.scaling = kept->kept;
    r.eceCalibrated = kept->ece;
    r.calibrated = kept->bins;
    r.eceIfCalibrated = expectedCalibrationErrorIfCalibrated(kept->confidence, 10);
    std::tie(r.sequential, r.sequencePrefixes) = sequentialScaling(folds, truth, C);
    int right = 0;
    for (std::size_t t = 0; t < all.size(); ++t)
        right += argmaxLowestIndex(all[t].data(), C) == allTruth[t];
    r.accuracy = static_cast<double>(right) / static_cast<double>(all.size());
    r.fitTaps = static_cast<int>(all.size());
    r.evaluationTaps = static_cast<int>(all.size());
    r.measured = true;
    return r;
}

}  // namespace activetouch
