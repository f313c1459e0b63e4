#pragma once
// The paper's histogram maximum-likelihood classifier (eq. 1, 2; docs/design.md §3).
//
// Per class c and taxel k, a histogram of all training samples over B uniform bins spanning that
// taxel's min..max over the training set; P_k(s|c) = (h + alpha) / (sum h + B alpha). A tap's
// class is argmax_c sum_k sum_t log P_k(s_tk | c), always in the log domain.
//
// Beyond the paper, a training sample may count not only in its own bin but spread over its
// neighbours by a Gaussian kernel of kernelSigma_bins (weights exp(-d^2 / 2 sigma^2) for bin
// distances d up to ceil(3 sigma), cut at the ends of the range and scaled so that each sample
// still adds 1): a kernel density estimate of P_k(s|c) instead of the raw histogram. With one
// training tap per class the raw histogram is as narrow as one tap's noise; a tap between
// training positions then lands in bins its class never saw. Zero gives the paper's histogram,
// whose decision equals scikit-learn's MultinomialNB(alpha, fit_prior=False) on per-(taxel, bin)
// counts.
//
// The log table is laid out [taxel][bin][class]: a tap touches few distinct (taxel, bin) cells,
// so the decision sums count x row over those cells instead of over all T x K samples.
// Ties break to the lowest class index. Samples outside the trained range clamp to the end bins;
// a taxel that never varied in training maps every sample to bin 0 (class-independent, so it
// never sways a decision); NaN maps to bin 0, +inf to the last bin.
#include <cstddef>
#include <cstdint>
#include <new>
#include <string>
#include <vector>

#include "core/tap/Tap.h"

namespace activetouch {

/// Allocates on cache-line boundaries, so that table rows whose length is a multiple of 8
/// doubles never straddle a line.
template <class T>
struct CacheLineAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlignment{64};
    CacheLineAllocator() = default;
    template <class U>
    CacheLineAllocator(const CacheLineAllocator<U>&) {}
    T* allocate(std::size_t n) {
        return static_cast<T*>(::operator new(n * sizeof(T), kAlignment));
    }
    void deallocate(T* p, std::size_t) { ::operator delete(p, kAlignment); }
    template <class U>
    bool operator==(const CacheLineAllocator<U>&) const {
        return true;
    }
};

/// The widest kernel a classifier accepts, in bins (a kernel this wide already spreads one count
/// over 300 bins).
inline constexpr double kMaxKernelSigma_bins = 50.0;

struct ClassifierSettings {
    int bins = 100;           ///< B (paper: 100)
    double smoothing = 0.01;  ///< alpha, additive pseudo-count per bin, > 0 (docs/results.md:
                              ///< chosen by validation)
    double kernelSigma_bins =
        0.0;  ///< 0 = the paper's histogram; docs/results.md: a choice beyond it
    /// Why the settings cannot train a classifier, or empty.
    std::string problem() const;
};

struct LabelledTap {
    const Tap* tap = nullptr;
    int cls = 0;
};

class HistogramClassifier {
public:
    HistogramClassifier() = default;

    /// Trains on `taps` (all with the same taxel count; every class in [0, classCount) needs at
    /// least one tap). Throws std::invalid_argument with a sentence otherwise.
    static HistogramClassifier train(const std::vector<LabelledTap>& taps, int classCount,
                                     const ClassifierSettings& settings);

    int classCount() const { return classes_; }
    int taxelCount() const { return taxels_; }
    int binCount() const { return bins_; }
    bool trained() const { return classes_ > 0; }
    double rangeMin(int taxel) const { return min_[static_cast<std::size_t>(taxel)]; }
    double rangeMax(int taxel) const { return max_[static_cast<std::size_t>(taxel)]; }

    /// Bin of `value` for `taxel`, with the clamping rules above.
    int binOf(int taxel, double value) const;

    /// log P_k(bin | class) for one cell.
    double logProbability(int taxel, int bin, int cls) const {
        return logTable_[(static_cast<std::size_t>(taxel) * static_cast<std::size_t>(bins_) +
                          static_cast<std::size_t>(bin)) *
                             static_cast<std::size_t>(classes_) +
                         static_cast<std::size_t>(cls)];
    }

    /// Sum over the tap's samples of log P for every class into `out` (classCount values).
    void logLikelihoods(const Tap& tap, double* out) const;

    /// The maximum-likelihood class (lowest index on ties): the same as the argmax of
    /// logLikelihoods(), found by scoring every class from a 16-bit fixed-point copy of the
    /// table in exact integer sums, bounding that score's error, and summing exactly only the
    /// classes within the bound of the best (none when one class alone is within it).
    int classify(const Tap& tap) const;

    /// Every class's log-likelihood as a percept that weighs all classes reads them (the
    /// continuous percept): exact, as logLikelihoods() gives them, for the classes that could be
    /// within kPerceptMarginNats of the best; the 16-bit screening score for the rest, within
    /// screeningBound(tap) of their exact sums. A fraction of logLikelihoods()' cost: the screen
    /// reads a quarter of the table's bytes.
    void perceptScores(const Tap& tap, double* out) const;
    static constexpr double kPerceptMarginNats = 60.0;
    /// How far a screening score can lie from the exact log-likelihood for `tap`, nats.
    double screeningBound(const Tap& tap) const;

    struct Decision {
        int cls = 0;
        double posterior = 0.0;  ///< of the winner, flat prior, normalised with log-sum-exp
    };
    Decision decide(const Tap& tap) const;

private:
    /// The exact log-likelihoods of `classes` (count of them) from a tap's distinct cells and
    /// their counts, into out[class]: each summed in the same order and operations as
    /// logLikelihoods(), so the same bits.
    void exactSums(const std::size_t* classes, std::size_t count, const std::uint32_t* cells,
                   const std::int32_t* counts, std::size_t distinct, double* out) const;
    /// The tap's distinct (taxel, bin) cells in ascending order with their sample counts, in
    /// thread-local buffers; returns how many. The cell after the last names the screening
    /// table's zero row.
    std::size_t tapCells(const Tap& tap, const std::uint32_t** cells,
                         const std::int32_t** counts) const;
    /// Exact scores (as logLikelihoods gives them) of the classes that could be within
    /// `marginNats` of the best (see classify()). For a `posterior`, the rest keep their
    /// screening scores and -1 is returned. Otherwise the rest are -inf, and a class alone within
    /// the margin is returned without any exact sum (-1 when there are several).
    int screenedScores(const Tap& tap, double marginNats, bool posterior, double* out) const;
    /// train()'s steps: each taxel's range over the training taps (checking them), the
    /// smoothed log probabilities, and the screening copies of the table.
    void readRanges(const std::vector<LabelledTap>& taps);
    void learnTable(const std::vector<LabelledTap>& taps, const ClassifierSettings& settings);
    void buildScreening();

    int classes_ = 0, taxels_ = 0, bins_ = 0;
    std::vector<double> min_, max_,
        scale_;  // per taxel; scale_ = bins / (max - min), 0 if degenerate
    std::vector<double> minTiled_, scaleTiled_;  // the same, repeated over a block of frames
    std::vector<std::uint32_t> cellBaseTiled_;   // taxel * bins, likewise
    std::vector<double, CacheLineAllocator<double>> logTable_;  // [taxel][bin][class]
    // For classify() and decide(): the table in 16-bit fixed point, log P = offset[cell] +
    // step * q[cell][class], rows padded to a multiple of 16 classes; the double table by class
    // ([class][taxel][bin]) for exact sums of a few classes; and the largest |log P|.
    std::vector<std::int16_t, CacheLineAllocator<std::int16_t>> screenTable_;
    std::vector<double> screenOffset_;
    double screenStep_ = 1.0;
    std::size_t screenStride_ = 0;
    std::vector<double, CacheLineAllocator<double>> logTableByClass_;
    double maxAbsLog_ = 0.0;
};

namespace detail {
/// A tap's count vector: the distinct cells among cellOf[0, samples) (each below `cellsTotal`),
/// ascending, into `cells` and their counts into `counts`; returns how many. Counters are read
/// back sixteen at a time (SSE2; one at a time off x86-64), or where the CPU has AVX2 and
/// `portable` is false, eight at a time by a permutation without a branch per cell; the two give
/// the same. `cells` and `counts` hold min(samples, cellsTotal) + kCountCellsSlack values (the
/// permutations store eight at a time).
inline constexpr std::size_t kCountCellsSlack = 8;
std::size_t countCells(const std::uint32_t* cellOf, std::size_t samples, std::size_t cellsTotal,
                       std::uint32_t* cells, std::int32_t* counts, bool portable);
/// The screening sums of classify(): out[c] = sum over i < rows of counts[i] *
/// table[cells[i] * stride + c] for c < stride (a multiple of 16), exact in 32-bit integers.
/// `cells[rows]` must name an all-zero row, and `counts[rows]` be readable (any value: it only
/// ever multiplies that row). By the portable loop, or where the CPU has AVX2 and
/// `portable` is false, by the vector kernel; the two give the same sums.
void screenSums(const std::int16_t* table, std::size_t stride, const std::uint32_t* cells,
                const std::int32_t* counts, std::size_t rows, std::int32_t* out, bool portable);
}  // namespace detail

/// Relative width of a tie: scores this close to the maximum are equal for the decision. Sums
/// that are equal in exact arithmetic can differ in the last bits when their terms are added in
/// another order; without this, such ties would break by rounding instead of by index.
inline constexpr double kTieTolerance = 1e-10;

/// Index of the largest value; among values within kTieTolerance (relative) of the largest, the
/// lowest index. NaN never wins.
int argmaxLowestIndex(const double* values, int count);

/// log(sum exp(values)), stable for any finite values.
double logSumExp(const double* values, int count);

/// sum exp(scale * gaps) for gaps <= 0 and scale > 0 (a term below e^-708 left out): the sum a
/// log-sum-exp takes once its largest value is subtracted, for many scales of the same values.
double sumExpScaled(const double* gaps, int count, double scale);

}  // namespace activetouch
