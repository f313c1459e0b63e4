#include "core/classify/HistogramClassifier.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace activetouch {

std::string ClassifierSettings::problem() const {
    if (bins < 1 || bins > 100000) return "bins must be between 1 and 100000, got " + std::to_string(bins);
    if (!(smoothing > 0.0) || !std::isfinite(smoothing))
        return "smoothing must be a positive number (zero would make unseen bins impossible)";
    return {};
}

int HistogramClassifier::binOf(int taxel, double value) const {
    const auto k = static_cast<std::size_t>(taxel);
    const double scale = scale_[k];
    if (scale == 0.0) return 0;
    if (!(value > min_[k])) return 0;  // also NaN
    if (!(value < max_[k])) return bins_ - 1;
    const int b = static_cast<int>((value - min_[k]) * scale);
    return std::min(b, bins_ - 1);
}

HistogramClassifier HistogramClassifier::train(const std::vector<LabelledTap>& taps, int classCount,
                                               const ClassifierSettings& settings) {
    if (auto p = settings.problem(); !p.empty()) throw std::invalid_argument(p);
    if (classCount < 1) throw std::invalid_argument("a classifier needs at least one class");
    if (taps.empty()) throw std::invalid_argument("no training taps");
    const int K = taps.front().tap->taxels;
    if (K < 1) throw std::invalid_argument("training taps have no taxels");

    HistogramClassifier c;
    c.classes_ = classCount;
    c.taxels_ = K;
    c.bins_ = settings.bins;
    c.min_.assign(static_cast<std::size_t>(K), std::numeric_limits<double>::infinity());
    c.max_.assign(static_cast<std::size_t>(K), -std::numeric_limits<double>::infinity());
    std::vector<int> tapsPerClass(static_cast<std::size_t>(classCount), 0);
    for (const auto& lt : taps) {
        if (lt.tap->taxels != K) throw std::invalid_argument("training taps differ in taxel count");
        if (lt.cls < 0 || lt.cls >= classCount)
            throw std::invalid_argument("training label " + std::to_string(lt.cls) + " is outside 0.." + std::to_string(classCount - 1));
        if (lt.tap->sampleCount() < 1) throw std::invalid_argument("a training tap has no samples");
        ++tapsPerClass[static_cast<std::size_t>(lt.cls)];
        for (std::size_t i = 0; i < lt.tap->samples.size(); ++i) {
            const double v = lt.tap->samples[i];
            if (!std::isfinite(v)) throw std::invalid_argument("a training tap holds a non-finite sample");
            const auto k = i % static_cast<std::size_t>(K);
            c.min_[k] = std::min(c.min_[k], v);
            c.max_[k] = std::max(c.max_[k], v);
        }
    }
    for (int cls = 0; cls < classCount; ++cls)
        if (tapsPerClass[static_cast<std::size_t>(cls)] == 0)
            throw std::invalid_argument("class " + std::to_string(cls) + " has no training tap");
    c.scale_.resize(static_cast<std::size_t>(K));
    for (std::size_t k = 0; k < static_cast<std::size_t>(K); ++k) {
        const double width = c.max_[k] - c.min_[k];
        c.scale_[k] = (width > 0.0 && std::isfinite(c.bins_ / width)) ? c.bins_ / width : 0.0;
    }

    // Counts per [taxel][bin][class], then smoothed log probabilities in place.
    const std::size_t B = static_cast<std::size_t>(c.bins_), C = static_cast<std::size_t>(classCount);
    c.logTable_.assign(static_cast<std::size_t>(K) * B * C, 0.0);
    std::vector<double> total(static_cast<std::size_t>(K) * C, 0.0);
    for (const auto& lt : taps) {
        const Tap& t = *lt.tap;
        for (int s = 0; s < t.sampleCount(); ++s) {
            for (int k = 0; k < K; ++k) {
                const auto b = static_cast<std::size_t>(c.binOf(k, t.at(s, k)));
                c.logTable_[(static_cast<std::size_t>(k) * B + b) * C + static_cast<std::size_t>(lt.cls)] += 1.0;
                total[static_cast<std::size_t>(k) * C + static_cast<std::size_t>(lt.cls)] += 1.0;
            }
        }
    }
    const double alpha = settings.smoothing;
    for (std::size_t k = 0; k < static_cast<std::size_t>(K); ++k) {
        for (std::size_t b = 0; b < B; ++b) {
            for (std::size_t cls = 0; cls < C; ++cls) {
                double& cell = c.logTable_[(k * B + b) * C + cls];
                cell = std::log(cell + alpha) - std::log(total[k * C + cls] + static_cast<double>(B) * alpha);
            }
        }
    }
    return c;
}

namespace {

// The hot loop: scores += count * row over the tap's distinct cells. Cloned for AVX2 where the
// CPU has it; the arithmetic is the same element-wise multiply-add, so decisions do not depend
// on which clone runs.
__attribute__((target_clones("avx2", "default")))
void accumulateRows(const double* table, std::size_t classes, const std::uint32_t* cells,
                    const std::uint32_t* counts, std::size_t cellCount, double* out) {
    for (std::size_t i = 0; i < cellCount; ++i) {
        const double* row = table + static_cast<std::size_t>(cells[i]) * classes;
        const double n = static_cast<double>(counts[i]);
        for (std::size_t c = 0; c < classes; ++c) out[c] += n * row[c];
    }
}

}  // namespace

void HistogramClassifier::logLikelihoods(const Tap& tap, double* out) const {
    const std::size_t C = static_cast<std::size_t>(classes_);
    std::fill(out, out + C, 0.0);
    if (tap.taxels != taxels_) throw std::invalid_argument("tap has " + std::to_string(tap.taxels) + " taxels, the classifier was trained on " + std::to_string(taxels_));

    // Count the tap's samples per (taxel, bin) cell, remembering which cells it touched.
    thread_local std::vector<std::uint32_t> counts;
    thread_local std::vector<std::uint32_t> touched;
    thread_local std::vector<std::uint32_t> touchedCounts;
    const std::size_t cellsTotal = static_cast<std::size_t>(taxels_) * static_cast<std::size_t>(bins_);
    if (counts.size() < cellsTotal) counts.assign(cellsTotal, 0);
    touched.clear();
    const int T = tap.sampleCount();
    const double* s = tap.samples.data();
    for (int t = 0; t < T; ++t) {
        for (int k = 0; k < taxels_; ++k) {
            const auto cell = static_cast<std::uint32_t>(k * bins_ + binOf(k, *s++));
            if (counts[cell]++ == 0) touched.push_back(cell);
        }
    }
    // Cells in ascending order make the summation order independent of sample order.
    std::sort(touched.begin(), touched.end());
    touchedCounts.resize(touched.size());
    for (std::size_t i = 0; i < touched.size(); ++i) {
        touchedCounts[i] = counts[touched[i]];
        counts[touched[i]] = 0;
    }
    accumulateRows(logTable_.data(), C, touched.data(), touchedCounts.data(), touched.size(), out);
}

int argmaxLowestIndex(const double* v, int n) {
    int best = -1;
    for (int i = 0; i < n; ++i)
        if (!std::isnan(v[i]) && (best < 0 || v[i] > v[best])) best = i;
    return best < 0 ? 0 : best;
}

double logSumExp(const double* v, int n) {
    double m = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) m = std::max(m, v[i]);
    if (!std::isfinite(m)) return m;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += std::exp(v[i] - m);
    return m + std::log(sum);
}

int HistogramClassifier::classify(const Tap& tap) const {
    thread_local std::vector<double> scores;
    scores.resize(static_cast<std::size_t>(classes_));
    logLikelihoods(tap, scores.data());
    return argmaxLowestIndex(scores.data(), classes_);
}

HistogramClassifier::Decision HistogramClassifier::decide(const Tap& tap) const {
    std::vector<double> scores(static_cast<std::size_t>(classes_));
    logLikelihoods(tap, scores.data());
    Decision d;
    d.cls = argmaxLowestIndex(scores.data(), classes_);
    d.posterior = std::exp(scores[static_cast<std::size_t>(d.cls)] - logSumExp(scores.data(), classes_));
    return d;
}

}  // namespace activetouch
