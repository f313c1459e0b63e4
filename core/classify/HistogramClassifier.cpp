#include "core/classify/HistogramClassifier.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "core/common/Avx2Clones.h"
#include "core/common/NumberText.h"

namespace activetouch {

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
    c.min_.assign(static_cast<std::size_t>(K), std::numeric_limits<double>::infinity());
    c.max_.assign(static_cast<std::size_t>(K), -std::numeric_limits<double>::infinity());
    std::vector<int> tapsPerClass(static_cast<std::size_t>(classCount), 0);
    for (const auto& lt : taps) {
        if (lt.tap->taxels != K) throw std::invalid_argument("training taps differ in taxel count");
        if (lt.cls < 0 || lt.cls >= classCount)
            throw std::invalid_argument("training label " + std::to_string(lt.cls) +
                                        " is outside 0.." + std::to_string(classCount - 1));
        if (lt.tap->sampleCount() < 1) throw std::invalid_argument("a training tap has no samples");
        ++tapsPerClass[static_cast<std::size_t>(lt.cls)];
        for (std::size_t i = 0; i < lt.tap->samples.size(); ++i) {
            const double v = lt.tap->samples[i];
            if (!std::isfinite(v))
                throw std::invalid_argument("a training tap holds a non-finite sample");
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

    // The per-taxel range tiled over a block of frames, for the vectorised binning.
    constexpr std::size_t kTileFrames = 64;
    for (std::size_t f = 0; f < kTileFrames; ++f) {
        for (std::size_t k = 0; k < static_cast<std::size_t>(K); ++k) {
            c.minTiled_.push_back(c.min_[k]);
            c.scaleTiled_.push_back(c.scale_[k]);
            c.cellBaseTiled_.push_back(
                static_cast<std::uint32_t>(k * static_cast<std::size_t>(c.bins_)));
        }
    }

    // Counts per [taxel][bin][class], then smoothed log probabilities in place.
    const std::size_t B = static_cast<std::size_t>(c.bins_),
                      C = static_cast<std::size_t>(classCount);
    c.logTable_.assign(static_cast<std::size_t>(K) * B * C, 0.0);
    std::vector<double> total(static_cast<std::size_t>(K) * C, 0.0);
    for (const auto& lt : taps) {
        const Tap& t = *lt.tap;
        for (int s = 0; s < t.sampleCount(); ++s) {
            for (int k = 0; k < K; ++k) {
                const auto b = static_cast<std::size_t>(c.binOf(k, t.at(s, k)));
                c.logTable_[(static_cast<std::size_t>(k) * B + b) * C +
                            static_cast<std::size_t>(lt.cls)] += 1.0;
                total[static_cast<std::size_t>(k) * C + static_cast<std::size_t>(lt.cls)] += 1.0;
            }
        }
    }
    if (settings.kernelSigma_bins > 0.0)
        spreadCounts(c.logTable_, K, B, C, settings.kernelSigma_bins);
    const double alpha = settings.smoothing;
    for (std::size_t k = 0; k < static_cast<std::size_t>(K); ++k) {
        for (std::size_t b = 0; b < B; ++b) {
            for (std::size_t cls = 0; cls < C; ++cls) {
                double& cell = c.logTable_[(k * B + b) * C + cls];
                cell = std::log(cell + alpha) -
                       std::log(total[k * C + cls] + static_cast<double>(B) * alpha);
            }
        }
    }
    // The screening copies (classify, decide).
    c.logTableF_.assign(c.logTable_.begin(), c.logTable_.end());
    const std::size_t cells = static_cast<std::size_t>(K) * B;
    c.logTableByClass_.resize(cells * C);
    c.cellMaxAbs_.assign(cells, 0.0);
    for (std::size_t cell = 0; cell < cells; ++cell)
        for (std::size_t cls = 0; cls < C; ++cls) {
            const double v = c.logTable_[cell * C + cls];
            c.logTableByClass_[cls * cells + cell] = v;
            c.cellMaxAbs_[cell] = std::max(c.cellMaxAbs_[cell], std::abs(v));
        }
    return c;
}

namespace {

// The hot loop: scores += count * row over the tap's distinct cells. Classes are taken in
// chunks whose partial sums stay in registers across all rows, so each score is stored once.
// Cloned for AVX2 where the CPU has it; every score sees the same multiplications and additions
// in the same order in either clone (no contraction into FMA), so decisions never depend on the
// CPU.
using Double4 = double __attribute__((vector_size(32)));

template <std::size_t Vectors>
__attribute__((always_inline)) inline void accumulateChunk(const double* const* rows,
                                                           const double* weights,
                                                           std::size_t rowCount, std::size_t c0,
                                                           double* out) {
    Double4 acc[Vectors] = {};
    // The rows are scattered over a table larger than a core's L2: fetch ahead of use.
    constexpr std::size_t kAhead = 10;
    for (std::size_t i = 0; i < std::min(kAhead, rowCount); ++i)
        for (std::size_t j = 0; j < Vectors; j += 2) __builtin_prefetch(rows[i] + c0 + 4 * j);
    for (std::size_t i = 0; i < rowCount; ++i) {
        if (i + kAhead < rowCount)
            for (std::size_t j = 0; j < Vectors; j += 2)
                __builtin_prefetch(rows[i + kAhead] + c0 + 4 * j);
        const double* row = rows[i] + c0;
        const Double4 n = {weights[i], weights[i], weights[i], weights[i]};
        for (std::size_t j = 0; j < Vectors; ++j) {
            Double4 r;
            std::memcpy(&r, row + 4 * j, sizeof r);
            acc[j] += n * r;
        }
    }
    std::memcpy(out + c0, acc, sizeof acc);
}

ACTIVETOUCH_AVX2_CLONES void accumulateRows(const double* const* rows, const double* weights,
                                            std::size_t rowCount, std::size_t classes,
                                            double* out) {
    std::size_t c0 = 0;
    for (; c0 + 24 <= classes; c0 += 24) accumulateChunk<6>(rows, weights, rowCount, c0, out);
    for (; c0 + 4 <= classes; c0 += 4) accumulateChunk<1>(rows, weights, rowCount, c0, out);
    for (; c0 < classes; ++c0) {
        double acc = 0.0;
        for (std::size_t i = 0; i < rowCount; ++i) acc += weights[i] * rows[i][c0];
        out[c0] = acc;
    }
}

// The same in single precision over the float table, for screening: 64 classes at a time.
using Float8 = float __attribute__((vector_size(32)));

template <std::size_t Vectors>
__attribute__((always_inline)) inline void accumulateChunkF(
    const float* table, const std::uint32_t* cells, const double* weights, std::size_t rowCount,
    std::size_t classes, std::size_t c0, float* out) {
    Float8 acc[Vectors] = {};
    for (std::size_t i = 0; i < rowCount; ++i) {
        const float* row = table + static_cast<std::size_t>(cells[i]) * classes + c0;
        const auto w = static_cast<float>(weights[i]);
        const Float8 n = {w, w, w, w, w, w, w, w};
        for (std::size_t j = 0; j < Vectors; ++j) {
            Float8 r;
            std::memcpy(&r, row + 8 * j, sizeof r);
            acc[j] += n * r;
        }
    }
    std::memcpy(out + c0, acc, sizeof acc);
}

ACTIVETOUCH_AVX2_CLONES void accumulateRowsF(const float* table, const std::uint32_t* cells,
                                             const double* weights, std::size_t rowCount,
                                             std::size_t classes, float* out) {
    std::size_t c0 = 0;
    for (; c0 + 64 <= classes; c0 += 64)
        accumulateChunkF<8>(table, cells, weights, rowCount, classes, c0, out);
    for (; c0 + 8 <= classes; c0 += 8)
        accumulateChunkF<1>(table, cells, weights, rowCount, classes, c0, out);
    for (; c0 < classes; ++c0) {
        float acc = 0.0f;
        for (std::size_t i = 0; i < rowCount; ++i)
            acc += static_cast<float>(weights[i]) *
                   table[static_cast<std::size_t>(cells[i]) * classes + c0];
        out[c0] = acc;
    }
}

// Bins of a block of samples. Branch-free so it vectorises over the flat block, with the per-
// taxel range tiled to the block's length: (v - min) * scale clamped to [0, B - 1]; NaN compares
// false and lands in bin 0; a degenerate taxel has scale 0 (and inf * 0 = NaN), so it lands in
// bin 0 too. Equal to binOf() for every value.
ACTIVETOUCH_AVX2_CLONES void binBlock(const double* __restrict samples, std::size_t count,
                                      const double* __restrict min, const double* __restrict scale,
                                      const std::uint32_t* __restrict cellBase, double lastBin,
                                      std::uint32_t* __restrict cells) {
    for (std::size_t i = 0; i < count; ++i) {
        double x = (samples[i] - min[i]) * scale[i];
        x = x > 0.0 ? x : 0.0;
        x = x < lastBin ? x : lastBin;
        cells[i] = cellBase[i] + static_cast<std::uint32_t>(x);
    }
}

}  // namespace

std::size_t HistogramClassifier::tapCells(const Tap& tap, const std::uint32_t** cellsOut,
                                          const double** countsOut) const {
    if (tap.taxels != taxels_)
        throw std::invalid_argument("tap has " + std::to_string(tap.taxels) +
                                    " taxels, the classifier was trained on " +
                                    std::to_string(taxels_));
    // The tap's count vector over (taxel, bin) cells: count samples per cell and mark the cells
    // touched in a bitmap, then visit the marked cells in ascending order (so every sum over
    // them does not depend on sample order) and clear as we go.
    thread_local std::vector<std::uint32_t> counts, cellOf, cells;
    thread_local std::vector<double> weights;
    thread_local std::vector<std::uint64_t> touched;
    const std::size_t cellsTotal =
        static_cast<std::size_t>(taxels_) * static_cast<std::size_t>(bins_);
    if (counts.size() < cellsTotal) {
        counts.assign(cellsTotal, 0);
        touched.assign((cellsTotal + 63) / 64, 0);
    }
    cellOf.resize(tap.samples.size());
    const std::size_t block = minTiled_.size();
    for (std::size_t start = 0; start < tap.samples.size(); start += block)
        binBlock(tap.samples.data() + start, std::min(block, tap.samples.size() - start),
                 minTiled_.data(), scaleTiled_.data(), cellBaseTiled_.data(),
                 static_cast<double>(bins_ - 1), cellOf.data() + start);
    std::uint32_t* const count = counts.data();
    std::uint64_t* const marks = touched.data();
    for (const std::uint32_t cell : cellOf) {
        ++count[cell];
        marks[cell >> 6] |= std::uint64_t{1} << (cell & 63);
    }
    cells.resize(std::min(cellOf.size(), cellsTotal));
    weights.resize(cells.size());
    std::size_t distinct = 0;
    const std::size_t words = (cellsTotal + 63) / 64;
    for (std::size_t w = 0; w < words; ++w) {
        std::uint64_t bits = marks[w];
        marks[w] = 0;
        while (bits) {
            const auto cell = static_cast<std::uint32_t>(
                w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits)));
            bits &= bits - 1;
            cells[distinct] = cell;
            weights[distinct++] = static_cast<double>(count[cell]);
            count[cell] = 0;
        }
    }
    *cellsOut = cells.data();
    *countsOut = weights.data();
    return distinct;
}

void HistogramClassifier::logLikelihoods(const Tap& tap, double* out) const {
    const std::size_t C = static_cast<std::size_t>(classes_);
    const std::uint32_t* cells = nullptr;
    const double* weights = nullptr;
    const std::size_t distinct = tapCells(tap, &cells, &weights);
    thread_local std::vector<const double*> rows;
    rows.resize(distinct);
    for (std::size_t i = 0; i < distinct; ++i)
        rows[i] = logTable_.data() + static_cast<std::size_t>(cells[i]) * C;
    accumulateRows(rows.data(), weights, distinct, C, out);
}

void HistogramClassifier::screenedScores(const Tap& tap, double marginNats, double* out) const {
    const std::size_t C = static_cast<std::size_t>(classes_);
    const std::uint32_t* cells = nullptr;
    const double* weights = nullptr;
    const std::size_t distinct = tapCells(tap, &cells, &weights);
    thread_local std::vector<float> rough;
    rough.resize(C);
    accumulateRowsF(logTableF_.data(), cells, weights, distinct, C, rough.data());
    // Each single-precision score is within `bound` of the exact one: every table entry is
    // rounded once (relative error u = 2^-24), every product once, and a sum of R terms errs by
    // at most R u times the sum of their magnitudes (the standard bound, doubled for margin).
    double magnitude = 0.0;
    for (std::size_t i = 0; i < distinct; ++i) magnitude += weights[i] * cellMaxAbs_[cells[i]];
    constexpr double u = 0x1p-24;
    const double bound = 2.0 * (static_cast<double>(distinct) + 3.0) * u * magnitude;
    float best = -std::numeric_limits<float>::infinity();
    for (float v : rough) best = std::max(best, v);
    // Classes that could be within `marginNats` of the exact maximum (or of a tie with it) are
    // summed exactly, in the same order and operations as logLikelihoods(); the rest keep their
    // single-precision score.
    const double floor = static_cast<double>(best) - 2.0 * bound - marginNats -
                         2.0 * kTieTolerance * (std::abs(static_cast<double>(best)) + bound + 1.0);
    const std::size_t cellsTotal =
        static_cast<std::size_t>(taxels_) * static_cast<std::size_t>(bins_);
    for (std::size_t c = 0; c < C; ++c) {
        if (!(static_cast<double>(rough[c]) >= floor) && std::isfinite(floor)) {
            out[c] = static_cast<double>(rough[c]);
            continue;
        }
        const double* row = logTableByClass_.data() + c * cellsTotal;
        double acc = 0.0;
        for (std::size_t i = 0; i < distinct; ++i) acc += weights[i] * row[cells[i]];
        out[c] = acc;
    }
}

int argmaxLowestIndex(const double* v, int n) {
    int best = -1;
    for (int i = 0; i < n; ++i)
        if (!std::isnan(v[i]) && (best < 0 || v[i] > v[best])) best = i;
    if (best < 0) return 0;
    const double m = v[best];
    if (!std::isfinite(m)) return best;
    const double floor = m - kTieTolerance * std::max(1.0, std::abs(m));
    for (int i = 0; i < best; ++i)
        if (!std::isnan(v[i]) && v[i] >= floor) return i;
    return best;
}

double logSumExp(const double* v, int n) {
    double m = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) m = std::max(m, v[i]);
    if (!std::isfinite(m)) return m;
    double sum = 0.0;
    // exp of anything below -746 is exactly 0 in a double: skipping it changes no bit.
    for (int i = 0; i < n; ++i)
        if (const double x = v[i] - m; x > -746.0) sum += std::exp(x);
    return m + std::log(sum);
}

int HistogramClassifier::classify(const Tap& tap) const {
    thread_local std::vector<double> scores;
    scores.resize(static_cast<std::size_t>(classes_));
    screenedScores(tap, 0.0, scores.data());  // every possible winner exact: the same argmax
    return argmaxLowestIndex(scores.data(), classes_);
}

HistogramClassifier::Decision HistogramClassifier::decide(const Tap& tap) const {
    // Classes more than 60 nats below the best add under e^-60 each to the normaliser, far
    // below any posterior's resolution; within that, every score is exact.
    thread_local std::vector<double> scores;
    scores.resize(static_cast<std::size_t>(classes_));
    screenedScores(tap, 60.0, scores.data());
    Decision d;
    d.cls = argmaxLowestIndex(scores.data(), classes_);
    d.posterior =
        std::exp(scores[static_cast<std::size_t>(d.cls)] - logSumExp(scores.data(), classes_));
    return d;
}

}  // namespace activetouch
