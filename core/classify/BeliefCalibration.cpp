#include "core/classify/BeliefCalibration.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace activetouch {

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
        const double c = std::isfinite(confidence[t]) ? std::clamp(confidence[t], 0.0, 1.0) : 0.0;
        const auto i =
            std::min(b.size() - 1, static_cast<std::size_t>(c * static_cast<double>(b.size())));
        ++b[i].taps;
        b[i].meanConfidence += c;
        b[i].accuracy += correct[t] ? 1.0 : 0.0;
    }
    double ece = 0.0;
    int total = 0;
    for (auto& bin : b) {
        if (bin.taps == 0) continue;
        bin.meanConfidence /= bin.taps;
        bin.accuracy /= bin.taps;
        ece += bin.taps * std::abs(bin.accuracy - bin.meanConfidence);
        total += bin.taps;
    }
    if (out) *out = b;
    return total > 0 ? ece / total : 0.0;
}

double scaledTopPosterior(const double* ll, int count, double scale, int* top) {
    // Scaled in place of a copy; NaN and -inf rule a class out; +inf can only come from a
    // broken table and is treated as the largest finite value.
    thread_local std::vector<double> v;
    v.resize(static_cast<std::size_t>(count));
    const double s = std::isfinite(scale) && scale > 0.0 ? scale : 0.0;
    for (int c = 0; c < count; ++c) {
        double x = ll[c];
        if (std::isnan(x)) x = -std::numeric_limits<double>::infinity();
        if (x == std::numeric_limits<double>::infinity()) x = std::numeric_limits<double>::max();
        v[static_cast<std::size_t>(c)] = s == 0.0 ? (std::isfinite(x) ? 0.0 : x) : s * x;
    }
    const int best = argmaxLowestIndex(v.data(), count);
    if (top) *top = best;
    const double norm = logSumExp(v.data(), count);
    if (!std::isfinite(norm) || !std::isfinite(v[static_cast<std::size_t>(best)]))
        return 1.0 / static_cast<double>(std::max(1, count));  // nothing to tell classes apart
    return std::clamp(std::exp(v[static_cast<std::size_t>(best)] - norm), 0.0, 1.0);
}

namespace {

double meanNegativeLogPosterior(const std::vector<std::vector<double>>& ll,
                                const std::vector<int>& truth, double scale) {
    double sum = 0.0;
    thread_local std::vector<double> v;
    for (std::size_t t = 0; t < ll.size(); ++t) {
        v.assign(ll[t].begin(), ll[t].end());
        for (double& x : v) x *= scale;
        const double norm = logSumExp(v.data(), static_cast<int>(v.size()));
        sum += norm - v[static_cast<std::size_t>(truth[t])];
    }
    return ll.empty() ? 0.0 : sum / static_cast<double>(ll.size());
}

}  // namespace

double fitLogLikelihoodScale(const std::vector<std::vector<double>>& ll,
                             const std::vector<int>& truth) {
    // Golden-section search over log10(scale) in [-8, 0]: the held-out negative log-likelihood
    // of a temperature is unimodal in it.
    double a = -8.0, b = 0.0;
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = meanNegativeLogPosterior(ll, truth, std::pow(10.0, x1));
    double f2 = meanNegativeLogPosterior(ll, truth, std::pow(10.0, x2));
    for (int i = 0; i < 80 && b - a > 1e-6; ++i) {
        if (f1 <= f2) {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = meanNegativeLogPosterior(ll, truth, std::pow(10.0, x1));
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = meanNegativeLogPosterior(ll, truth, std::pow(10.0, x2));
        }
    }
    return std::pow(10.0, 0.5 * (a + b));
}

BeliefCalibration calibrateBelief(const HistogramClassifier& classifier,
                                  const std::vector<const Tap*>& heldOut,
                                  const std::vector<int>& truth) {
    BeliefCalibration r;
    if (heldOut.size() < 4 || heldOut.size() != truth.size() || !classifier.trained()) return r;
    const int C = classifier.classCount();
    // Two folds of the held-out taps (even- and odd-numbered): each tap's calibrated confidence
    // comes from the factor fitted on the other fold, so every error is measured on taps the
    // factor never saw; the factor kept for use is fitted on them all.
    std::vector<std::vector<double>> ll[2];
    std::vector<int> fold[2];
    int samples = 0;
    for (std::size_t t = 0; t < heldOut.size(); ++t) {
        std::vector<double> v(static_cast<std::size_t>(C));
        classifier.logLikelihoods(*heldOut[t], v.data());
        samples = std::max(samples, heldOut[t]->sampleCount() * heldOut[t]->taxels);
        ll[t % 2].push_back(std::move(v));
        fold[t % 2].push_back(truth[t]);
    }
    const double foldScale[2] = {fitLogLikelihoodScale(ll[1], fold[1]),
                                 fitLogLikelihoodScale(ll[0], fold[0])};
    std::vector<std::vector<double>> all = ll[0];
    all.insert(all.end(), ll[1].begin(), ll[1].end());
    std::vector<int> allTruth = fold[0];
    allTruth.insert(allTruth.end(), fold[1].begin(), fold[1].end());
    r.fittedScale = fitLogLikelihoodScale(all, allTruth);
    r.perSampleScale = 1.0 / std::max(1, samples);
    // The expected calibration error with each tap's confidence at scale(fold).
    auto ece = [&](auto scaleOf, std::vector<ReliabilityBin>* bins) {
        std::vector<double> confidence;
        std::vector<bool> correct;
        for (int f = 0; f < 2; ++f)
            for (std::size_t t = 0; t < ll[f].size(); ++t) {
                int top = 0;
                confidence.push_back(scaledTopPosterior(ll[f][t].data(), C, scaleOf(f), &top));
                correct.push_back(top == fold[f][t]);
            }
        return expectedCalibrationError(confidence, correct, 10, bins);
    };
    std::vector<ReliabilityBin> fittedBins, perSampleBins;
    r.eceRaw = ece([](int) { return 1.0; }, &r.raw);
    r.eceFitted = ece([&](int f) { return foldScale[f]; }, &fittedBins);
    r.ecePerSample = ece([&](int) { return r.perSampleScale; }, &perSampleBins);
    const bool fitted = r.eceFitted <= r.ecePerSample;
    r.scale = fitted ? r.fittedScale : r.perSampleScale;
    r.method = fitted ? "temperature fitted on held-out taps" : "mean per sample";
    r.eceCalibrated = fitted ? r.eceFitted : r.ecePerSample;
    r.calibrated = fitted ? fittedBins : perSampleBins;
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
