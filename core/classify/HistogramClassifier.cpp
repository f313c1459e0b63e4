#include "core/classify/HistogramClassifier.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/classify/HistogramScreening.h"
#include "core/common/Avx2Clones.h"
#include "core/common/FastExp.h"
#include "core/common/NumberText.h"

namespace activetouch {

using namespace screening;

std::string ClassifierSettings::problem() const {
    if (bins < 1 || bins > 100000)
        return "bins must be between 1 and 100000, got " + std::to_string(bins);
    if (!(smoothing > 0.0) || !std::isfinite(smoothing))
        return "smoothing must be a positive number (zero would make unseen bins impossible)";
    if (!(kernelSigma_bins >= 0.0) || !(kernelSigma_bins <= kMaxKernelSigma_bins))
        return "kernel_sigma_bins must be between 0 (the paper's histogram) and " +
               numberText(kMaxKernelSigma_bins) + ", got " + numberText(kernelSigma_bins);
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

namespace {

// Spreads each (taxel, class) column of counts over neighbouring bins by a Gaussian of `sigma`
// bins, cut at the range's ends and scaled per source bin so that no count is lost.
void spreadCounts(std::vector<double, CacheLineAllocator<double>>& table, int taxels, std::size_t B,
                  std::size_t C, double sigma) {
    const auto reach = static_cast<std::ptrdiff_t>(std::ceil(3.0 * sigma));
    const auto nBins = static_cast<std::ptrdiff_t>(B);
    std::vector<double> weight(static_cast<std::size_t>(2 * reach + 1));
    for (std::ptrdiff_t d = -reach; d <= reach; ++d)
        weight[static_cast<std::size_t>(d + reach)] =
            std::exp(-0.5 * static_cast<double>(d * d) / (sigma * sigma));
    // The first and last in-range bin a count in bin `src` reaches, and the weight they sum to.
    const auto first = [&](std::ptrdiff_t src) { return std::max<std::ptrdiff_t>(0, src - reach); };
    const auto last = [&](std::ptrdiff_t src) { return std::min(nBins - 1, src + reach); };
    std::vector<double> inRange(B, 0.0);
    for (std::ptrdiff_t src = 0; src < nBins; ++src)
        for (std::ptrdiff_t dst = first(src); dst <= last(src); ++dst)
            inRange[static_cast<std::size_t>(src)] +=
                weight[static_cast<std::size_t>(dst - src + reach)];
    std::vector<double> column(B), spread(B);
    for (std::size_t k = 0; k < static_cast<std::size_t>(taxels); ++k) {
        for (std::size_t cls = 0; cls < C; ++cls) {
            for (std::size_t b = 0; b < B; ++b) column[b] = table[(k * B + b) * C + cls];
            std::fill(spread.begin(), spread.end(), 0.0);
            for (std::ptrdiff_t src = 0; src < nBins; ++src) {
                const double n = column[static_cast<std::size_t>(src)];
                if (n == 0.0) continue;
                const double scale = n / inRange[static_cast<std::size_t>(src)];
                for (std::ptrdiff_t dst = first(src); dst <= last(src); ++dst)
                    spread[static_cast<std::size_t>(dst)] +=
                        scale * weight[static_cast<std::size_t>(dst - src + reach)];
            }
            for (std::size_t b = 0; b < B; ++b) table[(k * B + b) * C + cls] = spread[b];
        }
    }
}

}  // namespace

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
    c.readRanges(taps);
    c.learnTable(taps, settings);
    c.buildScreening();
    return c;
}

void HistogramClassifier::readRanges(const std::vector<LabelledTap>& taps) {
    const int K = taxels_;
    min_.assign(static_cast<std::size_t>(K), std::numeric_limits<double>::infinity());
    max_.assign(static_cast<std::size_t>(K), -std::numeric_limits<double>::infinity());
    std::vector<int> tapsPerClass(static_cast<std::size_t>(classes_), 0);
    for (const auto& lt : taps) {
        if (lt.tap->taxels != K) throw std::invalid_argument("training taps differ in taxel count");
        if (lt.cls < 0 || lt.cls >= classes_)
            throw std::invalid_argument("training label " + std::to_string(lt.cls) +
                                        " is outside 0.." + std::to_string(classes_ - 1));
        if (lt.tap->sampleCount() < 1) throw std::invalid_argument("a training tap has no samples");
        ++tapsPerClass[static_cast<std::size_t>(lt.cls)];
        for (std::size_t i = 0; i < lt.tap->samples.size(); ++i) {
            const double v = lt.tap->samples[i];
            if (!std::isfinite(v))
                throw std::invalid_argument("a training tap holds a non-finite sample");
            const auto k = i % static_cast<std::size_t>(K);
            min_[k] = std::min(min_[k], v);
            max_[k] = std::max(max_[k], v);
        }
    }
    for (int cls = 0; cls < classes_; ++cls)
        if (tapsPerClass[static_cast<std::size_t>(cls)] == 0)
            throw std::invalid_argument("class " + std::to_string(cls) + " has no training tap");
    scale_.resize(static_cast<std::size_t>(K));
    for (std::size_t k = 0; k < static_cast<std::size_t>(K); ++k) {
        const double width = max_[k] - min_[k];
        scale_[k] = (width > 0.0 && std::isfinite(bins_ / width)) ? bins_ / width : 0.0;
    }
    // The per-taxel range tiled over a block of frames, for the vectorised binning.
    constexpr std::size_t kTileFrames = 64;
    for (std::size_t f = 0; f < kTileFrames; ++f) {
        for (std::size_t k = 0; k < static_cast<std::size_t>(K); ++k) {
            minTiled_.push_back(min_[k]);
            scaleTiled_.push_back(scale_[k]);
            cellBaseTiled_.push_back(
                static_cast<std::uint32_t>(k * static_cast<std::size_t>(bins_)));
        }
    }
}

void HistogramClassifier::learnTable(const std::vector<LabelledTap>& taps,
                                     const ClassifierSettings& settings) {
    // Counts per [taxel][bin][class], then smoothed log probabilities in place.
    const int K = taxels_;
    const std::size_t B = static_cast<std::size_t>(bins_), C = static_cast<std::size_t>(classes_);
    logTable_.assign(static_cast<std::size_t>(K) * B * C, 0.0);
    std::vector<double> total(static_cast<std::size_t>(K) * C, 0.0);
    for (const auto& lt : taps) {
        const Tap& t = *lt.tap;
        for (int s = 0; s < t.sampleCount(); ++s) {
            for (int k = 0; k < K; ++k) {
                const auto b = static_cast<std::size_t>(binOf(k, t.at(s, k)));
                logTable_[(static_cast<std::size_t>(k) * B + b) * C +
                          static_cast<std::size_t>(lt.cls)] += 1.0;
                total[static_cast<std::size_t>(k) * C + static_cast<std::size_t>(lt.cls)] += 1.0;
            }
        }
    }
    if (settings.kernelSigma_bins > 0.0)
        spreadCounts(logTable_, K, B, C, settings.kernelSigma_bins);
    const double alpha = settings.smoothing;
    for (std::size_t k = 0; k < static_cast<std::size_t>(K); ++k) {
        for (std::size_t b = 0; b < B; ++b) {
            for (std::size_t cls = 0; cls < C; ++cls) {
                double& cell = logTable_[(k * B + b) * C + cls];
                cell = std::log(cell + alpha) -
                       std::log(total[k * C + cls] + static_cast<double>(B) * alpha);
            }
        }
    }
}

void HistogramClassifier::buildScreening() {
    // Each cell's row is stored about its midrange in steps of one size for the whole table, the
    // widest half-range taking the full 16 bits.
    const std::size_t C = static_cast<std::size_t>(classes_);
    const std::size_t cells = static_cast<std::size_t>(taxels_) * static_cast<std::size_t>(bins_);
    logTableByClass_.resize(cells * C);
    screenOffset_.assign(cells, 0.0);
    double widestHalfRange = 0.0;
    for (std::size_t cell = 0; cell < cells; ++cell) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (std::size_t cls = 0; cls < C; ++cls) {
            const double v = logTable_[cell * C + cls];
            logTableByClass_[cls * cells + cell] = v;
            maxAbsLog_ = std::max(maxAbsLog_, std::abs(v));
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
        screenOffset_[cell] = 0.5 * (lo + hi);
        widestHalfRange = std::max(widestHalfRange, 0.5 * (hi - lo));
    }
    screenStep_ = widestHalfRange > 0.0 ? widestHalfRange / kScreenLevels : 1.0;
    screenStride_ = (C + 15) / 16 * 16;
    // One row more, all zeros: the partner of an odd row out in the pairwise sums.
    screenTable_.assign((cells + 1) * screenStride_, 0);
    for (std::size_t cell = 0; cell < cells; ++cell)
        for (std::size_t cls = 0; cls < C; ++cls) {
            const double q =
                std::nearbyint((logTable_[cell * C + cls] - screenOffset_[cell]) / screenStep_);
            screenTable_[cell * screenStride_ + cls] =
                static_cast<std::int16_t>(std::clamp(q, -kScreenLevels, kScreenLevels));
        }
}

namespace {

// The largest value, NaN left out (as std::max(m, v) leaves it): several to an instruction.
ACTIVETOUCH_AVX2_CLONES double largest(const double* v, int n) {
    double m = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) m = v[i] > m ? v[i] : m;
    return m;
}

}  // namespace

int argmaxLowestIndex(const double* v, int n) {
    // The largest found several to an instruction; the answer is then the first value within the
    // tolerance of it (the largest itself if none comes before it). A comparison with NaN is
    // false: NaN never wins.
    const double m = largest(v, n);
    const double floor =
        std::isfinite(m) ? m - kTieTolerance * std::max(1.0, std::abs(m)) : m;  // +-inf: itself
    for (int i = 0; i < n; ++i)
        if (v[i] >= floor) return i;
    return 0;  // every value NaN
}

namespace {

// The sum of e^(scale * v - shift) over the values, a term below e^-708 (or a NaN, or
// -infinity) left out: four running sums over the values in turn, added in a fixed order, so that
// the terms are worked out several to an instruction and the sum is the same in either clone.
ACTIVETOUCH_AVX2_CLONES double expSum(const double* v, int n, double scale, double shift) {
    double sum[4] = {0.0, 0.0, 0.0, 0.0};
    int i = 0;
    for (; i + 4 <= n; i += 4)
        for (int j = 0; j < 4; ++j) {
            const double x = scale * v[i + j] - shift;
            const double e = expNonPositive(x);
            sum[j] += x > kExpFloor ? e : 0.0;
        }
    for (; i < n; ++i) {
        const double x = scale * v[i] - shift;
        const double e = expNonPositive(x);
        sum[0] += x > kExpFloor ? e : 0.0;
    }
    return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

}  // namespace

double sumExpScaled(const double* gaps, int count, double scale) {
    return expSum(gaps, count, scale, 0.0);
}

double logSumExp(const double* v, int n) {
    const double m = largest(v, n);
    if (!std::isfinite(m)) return m;
    // The largest term is e^0 = 1: one below e^-708 is lost beside it.
    return m + std::log(expSum(v, n, 1.0, m));
}

int HistogramClassifier::classify(const Tap& tap) const {
    thread_local std::vector<double> scores;
    scores.resize(static_cast<std::size_t>(classes_));
    // Every possible winner exact, or the one possible winner known: the same argmax.
    const int alone = screenedScores(tap, 0.0, false, scores.data());
    return alone >= 0 ? alone : argmaxLowestIndex(scores.data(), classes_);
}

HistogramClassifier::Decision HistogramClassifier::decide(const Tap& tap) const {
    // Classes more than 60 nats below the best add under e^-60 each to the normaliser, far
    // below any posterior's resolution; within that, every score is exact.
    thread_local std::vector<double> scores;
    scores.resize(static_cast<std::size_t>(classes_));
    screenedScores(tap, 60.0, true, scores.data());
    Decision d;
    d.cls = argmaxLowestIndex(scores.data(), classes_);
    d.posterior =
        std::exp(scores[static_cast<std::size_t>(d.cls)] - logSumExp(scores.data(), classes_));
    return d;
}

void HistogramClassifier::exactSums(const std::size_t* classes, std::size_t count,
                                    const std::uint32_t* cells, const std::int32_t* counts,
                                    std::size_t distinct, double* out) const {
    const std::size_t cellsTotal =
        static_cast<std::size_t>(taxels_) * static_cast<std::size_t>(bins_);
    thread_local std::vector<double> weight;
    weight.resize(distinct);
    for (std::size_t i = 0; i < distinct; ++i) weight[i] = static_cast<double>(counts[i]);
    const double* w = weight.data();
    auto rowOf = [&](std::size_t k) { return logTableByClass_.data() + classes[k] * cellsTotal; };
    // Four classes at a time: four running sums, so that each addition need not wait for the
    // last; each class's sum keeps its own order.
    std::size_t k = 0;
    for (; k + 4 <= count; k += 4) {
        const double *r0 = rowOf(k), *r1 = rowOf(k + 1), *r2 = rowOf(k + 2), *r3 = rowOf(k + 3);
        double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
        for (std::size_t i = 0; i < distinct; ++i) {
            const std::uint32_t cell = cells[i];
            a0 += w[i] * r0[cell];
            a1 += w[i] * r1[cell];
            a2 += w[i] * r2[cell];
            a3 += w[i] * r3[cell];
        }
        out[classes[k]] = a0;
        out[classes[k + 1]] = a1;
        out[classes[k + 2]] = a2;
        out[classes[k + 3]] = a3;
    }
    for (; k < count; ++k) {
        const double* row = rowOf(k);
        double acc = 0.0;
        for (std::size_t i = 0; i < distinct; ++i) acc += w[i] * row[cells[i]];
        out[classes[k]] = acc;
    }
}

}  // namespace activetouch
