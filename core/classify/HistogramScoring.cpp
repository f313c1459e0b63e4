// The classifier's per-tap scoring: a tap's distinct (taxel, bin) cells and their counts, the
// exact log-likelihoods from them, and the integer screen that leaves out classes that cannot
// win. The kernels and the members that call them share this file so that they inline together.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "core/classify/HistogramClassifier.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "core/classify/HistogramScreening.h"
#include "core/common/Avx2Clones.h"

namespace activetouch {

using namespace screening;

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

// The screening sums, exact in 32-bit integers: out[c] = sum_i counts[i] * q[cells[i]][c] for
// every padded class. Integer sums do not depend on their order, so both builds give the same.
void screenSumsPortable(const std::int16_t* table, std::size_t stride, const std::uint32_t* cells,
                        const std::int32_t* counts, std::size_t rows, std::int32_t* out) {
    std::fill(out, out + stride, 0);
    for (std::size_t i = 0; i < rows; ++i) {
        const std::int16_t* row = table + static_cast<std::size_t>(cells[i]) * stride;
        const std::int32_t n = counts[i];
        for (std::size_t c = 0; c < stride; ++c) out[c] += n * row[c];
    }
}

#if defined(__x86_64__)
// Two rows at a time: their levels interleaved 16 bits apart, multiplied by the two counts and
// added pairwise (vpmaddwd), for `Blocks` blocks of 16 classes held in registers over all rows.
// Within each 128-bit lane, the low unpack holds classes 0-3 (8-11), the high one 4-7 (12-15).
template <std::size_t Blocks, bool Prefetch>
__attribute__((target("avx2"), always_inline)) inline void screenChunkAvx2(
    const std::int16_t* table, std::size_t stride, const std::uint32_t* cells,
    const std::int32_t* counts, std::size_t rows, std::size_t c0, std::int32_t* out) {
    __m256i lo[Blocks], hi[Blocks];
    for (std::size_t j = 0; j < Blocks; ++j) lo[j] = hi[j] = _mm256_setzero_si256();
    // The zero row after the table, named by cells[rows], partners an odd last row.
    const auto rowAt = [&](std::size_t i) {
        return table + static_cast<std::size_t>(cells[i]) * stride + c0;
    };
    // The rows are scattered over the table: where it outgrows the cache, fetch ahead of use.
    constexpr std::size_t kAhead = 8;
    for (std::size_t i = 0; i < rows; i += 2) {
        if (Prefetch && i + kAhead + 1 < rows)
            for (std::size_t j = 0; j < Blocks; j += 2) {
                __builtin_prefetch(rowAt(i + kAhead) + 16 * j);
                __builtin_prefetch(rowAt(i + kAhead + 1) + 16 * j);
            }
        const std::int16_t* a = rowAt(i);
        const std::int16_t* b = rowAt(i + 1);
        const auto w = static_cast<std::uint32_t>(static_cast<std::uint16_t>(counts[i])) |
                       static_cast<std::uint32_t>(counts[i + 1]) << 16;
        const __m256i weights = _mm256_set1_epi32(static_cast<int>(w));
        for (std::size_t j = 0; j < Blocks; ++j) {
            const __m256i va = _mm256_load_si256(reinterpret_cast<const __m256i*>(a + 16 * j));
            const __m256i vb = _mm256_load_si256(reinterpret_cast<const __m256i*>(b + 16 * j));
            lo[j] =
                _mm256_add_epi32(lo[j], _mm256_madd_epi16(_mm256_unpacklo_epi16(va, vb), weights));
            hi[j] =
                _mm256_add_epi32(hi[j], _mm256_madd_epi16(_mm256_unpackhi_epi16(va, vb), weights));
        }
    }
    for (std::size_t j = 0; j < Blocks; ++j) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + c0 + 16 * j),
                            _mm256_permute2x128_si256(lo[j], hi[j], 0x20));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + c0 + 16 * j + 8),
                            _mm256_permute2x128_si256(lo[j], hi[j], 0x31));
    }
}

template <bool Prefetch>
__attribute__((target("avx2"))) void screenSumsAvx2Rows(const std::int16_t* table,
                                                        std::size_t stride,
                                                        const std::uint32_t* cells,
                                                        const std::int32_t* counts,
                                                        std::size_t rows, std::int32_t* out) {
    std::size_t c0 = 0;
    for (; c0 + 80 <= stride; c0 += 80)
        screenChunkAvx2<5, Prefetch>(table, stride, cells, counts, rows, c0, out);
    for (; c0 < stride; c0 += 16)
        screenChunkAvx2<1, Prefetch>(table, stride, cells, counts, rows, c0, out);
}

__attribute__((target("avx2"))) void screenSumsAvx2(const std::int16_t* table, std::size_t stride,
                                                    const std::uint32_t* cells,
                                                    const std::int32_t* counts, std::size_t rows,
                                                    std::int32_t* out) {
    // A table this small stays in a core's L2 from one tap to the next (the paper's 72 classes
    // take 192 KB); fetching ahead would only add instructions.
    constexpr std::size_t kResidentBytes = 256 * 1024;
    if (stride * sizeof(std::int16_t) * cells[rows] <= kResidentBytes)
        screenSumsAvx2Rows<false>(table, stride, cells, counts, rows, out);
    else
        screenSumsAvx2Rows<true>(table, stride, cells, counts, rows, out);
}
#endif

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
        // x is in [0, B - 1]: the signed conversion, which the vector units have, is exact.
        cells[i] = cellBase[i] + static_cast<std::uint32_t>(static_cast<std::int32_t>(x));
    }
}

// Bit j of masks[g] set where counter j of group g (of 16) is not zero: by SSE2, which every
// x86-64 has (saturating packs keep a nonzero count nonzero, down to one byte per counter), or
// one at a time elsewhere.
void touchedGroups16(const std::uint32_t* n, std::size_t groups, std::uint32_t* masks) {
    for (std::size_t g = 0; g < groups; ++g) {
        const std::uint32_t* group = n + 16 * g;
#if defined(__x86_64__)
        const auto* at = reinterpret_cast<const __m128i*>(group);
        const __m128i bytes =
            _mm_packs_epi16(_mm_packs_epi32(_mm_loadu_si128(at), _mm_loadu_si128(at + 1)),
                            _mm_packs_epi32(_mm_loadu_si128(at + 2), _mm_loadu_si128(at + 3)));
        masks[g] = static_cast<std::uint32_t>(
                       _mm_movemask_epi8(_mm_cmpeq_epi8(bytes, _mm_setzero_si128()))) ^
                   0xffffu;
#else
        std::uint32_t touched = 0;
        for (std::size_t j = 0; j < 16; ++j) touched |= (group[j] != 0 ? 1u : 0u) << j;
        masks[g] = touched;
#endif
    }
}

#if defined(__x86_64__)
// The same for groups of 32: the packs work within each 128-bit half, and a permutation puts the
// bytes back in counter order.
__attribute__((target("avx2"))) void touchedGroups32(const std::uint32_t* n, std::size_t groups,
                                                     std::uint32_t* masks) {
    const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
    for (std::size_t g = 0; g < groups; ++g) {
        const auto* at = reinterpret_cast<const __m256i*>(n + 32 * g);
        const __m256i mixed = _mm256_packs_epi16(
            _mm256_packs_epi32(_mm256_loadu_si256(at), _mm256_loadu_si256(at + 1)),
            _mm256_packs_epi32(_mm256_loadu_si256(at + 2), _mm256_loadu_si256(at + 3)));
        const __m256i bytes = _mm256_permutevar8x32_epi32(mixed, order);
        masks[g] = ~static_cast<std::uint32_t>(
            _mm256_movemask_epi8(_mm256_cmpeq_epi8(bytes, _mm256_setzero_si256())));
    }
}
#endif

#if defined(__x86_64__)
// For each byte value, the positions of its set bits in ascending order (padded with zeros), one
// byte each: the permutation that gathers a group of eight counters' touched ones to its front.
struct GatherOrders {
    std::uint64_t order[256];
};
constexpr GatherOrders makeGatherOrders() {
    GatherOrders t{};
    for (unsigned bits = 0; bits < 256; ++bits) {
        unsigned at = 0;
        for (unsigned j = 0; j < 8; ++j)
            if (bits & (1u << j)) t.order[bits] |= std::uint64_t{j} << (8 * at++);
    }
    return t;
}
constexpr GatherOrders kGatherOrders = makeGatherOrders();

// The touched counters of n, read back without a branch per cell: `marks` holds one byte per
// eight counters (bit j set where counter j is touched), `markBytes` of them, a multiple of 32.
// Each nonzero byte's counters are gathered to the front by one permutation and stored whole
// (up to seven values past the last are overwritten), then cleared.
__attribute__((target("avx2,popcnt"))) std::size_t gatherTouched(std::uint32_t* n,
                                                                 const std::uint8_t* marks,
                                                                 std::size_t markBytes,
                                                                 std::uint32_t* cells,
                                                                 std::int32_t* counts) {
    std::size_t distinct = 0;
    const __m256i zero = _mm256_setzero_si256();
    for (std::size_t w = 0; w < markBytes; w += 32) {
        const __m256i word = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(marks + w));
        auto nonzero =
            ~static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(word, zero)));
        while (nonzero) {
            const std::size_t b = w + static_cast<std::size_t>(__builtin_ctz(nonzero));
            nonzero &= nonzero - 1;
            const unsigned bits = marks[b];
            const __m256i order = _mm256_cvtepu8_epi32(
                _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&kGatherOrders.order[bits])));
            auto* group = reinterpret_cast<__m256i*>(n + 8 * b);
            const __m256i values = _mm256_loadu_si256(group);
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(counts + distinct),
                                _mm256_permutevar8x32_epi32(values, order));
            _mm256_storeu_si256(
                reinterpret_cast<__m256i*>(cells + distinct),
                _mm256_add_epi32(order, _mm256_set1_epi32(static_cast<int>(8 * b))));
            _mm256_storeu_si256(group, zero);
            distinct += static_cast<std::size_t>(__builtin_popcount(bits));
        }
    }
    return distinct;
}
#endif

// The touched counters of n, one at a time from the masks of its groups of 16, each touched
// group cleared.
std::size_t readTouched(std::uint32_t* n, const std::vector<std::uint32_t>& masks,
                        std::uint32_t* cells, std::int32_t* counts) {
    std::size_t distinct = 0;
    for (std::size_t g = 0; g < masks.size(); ++g) {
        std::uint32_t touched = masks[g];
        if (touched == 0) continue;
        std::uint32_t* const first = n + g * 16;
        while (touched) {
            const auto j = static_cast<std::size_t>(__builtin_ctz(touched));
            touched &= touched - 1;
            cells[distinct] = static_cast<std::uint32_t>(g * 16 + j);
            counts[distinct++] = static_cast<std::int32_t>(first[j]);
        }
        std::memset(first, 0, 16 * sizeof(std::uint32_t));
    }
    return distinct;
}

// A tap's count vector over (taxel, bin) cells: a 32-bit counter per cell (byte counters were
// measured several times slower on the machines of docs/benchmarks.md, their stores being
// slow).
class CellCounter {
public:
    /// Counts `samples` cells, writes the distinct ones ascending into `cells` and their counts
    /// into `counts` (so that every sum over them does not depend on sample order), and clears
    /// the counters for the next tap; returns how many.
    std::size_t count(const std::uint32_t* cellOf, std::size_t samples, std::size_t cellsTotal,
                      std::uint32_t* cells, std::int32_t* counts, bool portable) {
        constexpr std::size_t kGroups = 32;  // a multiple of every group size
        const std::size_t padded = (cellsTotal + kGroups - 1) / kGroups * kGroups;
        if (counters_.size() < padded) counters_.assign(padded, 0);
        std::uint32_t* const n = counters_.data();
        std::size_t i = 0;
        for (; i + 8 <= samples; i += 8)
            for (std::size_t j = 0; j < 8; ++j) ++n[cellOf[i + j]];
        for (; i < samples; ++i) ++n[cellOf[i]];
#if defined(__x86_64__)
        if (!portable && cpuHasAvx2()) {
            // Marks for the groups of 32, one byte per eight counters (x86-64 is little-endian:
            // byte b of a group's mark covers its counters 8b to 8b + 7), padded with unmarked
            // bytes to whole words of 32.
            if (const std::size_t words = (padded / 32 + 7) / 8 * 8; marks_.size() != words)
                marks_.assign(words, 0);
            touchedGroups32(n, padded / 32, marks_.data());
            // The padding words are read too: clear what an earlier, larger table left there,
            // or its groups would be read back as cells of this one.
            std::fill(marks_.begin() + static_cast<std::ptrdiff_t>(padded / 32), marks_.end(), 0u);
            return gatherTouched(n, reinterpret_cast<const std::uint8_t*>(marks_.data()),
                                 marks_.size() * 4, cells, counts);
        }
#endif
        masks_.resize(padded / 16);
        touchedGroups16(n, masks_.size(), masks_.data());
        return readTouched(n, masks_, cells, counts);
    }

private:
    std::vector<std::uint32_t> counters_, masks_, marks_;
};

}  // namespace

namespace detail {

std::size_t countCells(const std::uint32_t* cellOf, std::size_t samples, std::size_t cellsTotal,
                       std::uint32_t* cells, std::int32_t* counts, bool portable) {
    thread_local CellCounter counter;
    return counter.count(cellOf, samples, cellsTotal, cells, counts, portable);
}

void screenSums(const std::int16_t* table, std::size_t stride, const std::uint32_t* cells,
                const std::int32_t* counts, std::size_t rows, std::int32_t* out, bool portable) {
#if defined(__x86_64__)
    if (!portable && cpuHasAvx2()) return screenSumsAvx2(table, stride, cells, counts, rows, out);
#endif
    screenSumsPortable(table, stride, cells, counts, rows, out);
}

}  // namespace detail

namespace {

// The lead among a tap's screening sums: the first class with the largest, the floor `reach`
// levels below it, and how many classes lie at or above that floor.
struct ScreenLead {
    int first = 0;
    std::int32_t floor = 0;
    int within = 0;
};

ACTIVETOUCH_AVX2_CLONES ScreenLead screenLead(const std::int32_t* sums, std::size_t count,
                                              std::int64_t reach) {
    std::int32_t best = std::numeric_limits<std::int32_t>::min();
    for (std::size_t c = 0; c < count; ++c) best = std::max(best, sums[c]);
    ScreenLead lead;
    lead.floor = static_cast<std::int32_t>(std::max<std::int64_t>(
        std::int64_t{best} - reach, std::numeric_limits<std::int32_t>::min()));
    const auto noClass = static_cast<std::int32_t>(count);
    std::int32_t first = noClass;
    std::int32_t within = 0;
    for (std::size_t c = 0; c < count; ++c) {
        within += sums[c] >= lead.floor ? 1 : 0;
        first = std::min(first, sums[c] == best ? static_cast<std::int32_t>(c) : noClass);
    }
    lead.first = first;
    lead.within = within;
    return lead;
}

}  // namespace

std::size_t HistogramClassifier::tapCells(const Tap& tap, const std::uint32_t** cellsOut,
                                          const std::int32_t** countsOut) const {
    if (tap.taxels != taxels_)
        throw std::invalid_argument("tap has " + std::to_string(tap.taxels) +
                                    " taxels, the classifier was trained on " +
                                    std::to_string(taxels_));
    thread_local std::vector<std::uint32_t> cellOf, cells;
    thread_local std::vector<std::int32_t> weights;
    const std::size_t cellsTotal =
        static_cast<std::size_t>(taxels_) * static_cast<std::size_t>(bins_);
    cellOf.resize(tap.samples.size());
    const std::size_t block = minTiled_.size();
    for (std::size_t start = 0; start < tap.samples.size(); start += block)
        binBlock(tap.samples.data() + start, std::min(block, tap.samples.size() - start),
                 minTiled_.data(), scaleTiled_.data(), cellBaseTiled_.data(),
                 static_cast<double>(bins_ - 1), cellOf.data() + start);
    // Room past the cells that can be touched: for the counters' read-back, which stores eight at
    // a time, and for the end marker, which names the screening table's zero row.
    cells.resize(std::min(cellOf.size(), cellsTotal) + detail::kCountCellsSlack);
    weights.resize(cells.size());
    const std::size_t distinct = detail::countCells(cellOf.data(), cellOf.size(), cellsTotal,
                                                    cells.data(), weights.data(), false);
    cells[distinct] = static_cast<std::uint32_t>(cellsTotal);
    weights[distinct] = 0;
    *cellsOut = cells.data();
    *countsOut = weights.data();
    return distinct;
}

void HistogramClassifier::logLikelihoods(const Tap& tap, double* out) const {
    const std::size_t C = static_cast<std::size_t>(classes_);
    const std::uint32_t* cells = nullptr;
    const std::int32_t* counts = nullptr;
    const std::size_t distinct = tapCells(tap, &cells, &counts);
    thread_local std::vector<const double*> rows;
    thread_local std::vector<double> weights;
    rows.resize(distinct);
    weights.resize(distinct);
    for (std::size_t i = 0; i < distinct; ++i) {
        rows[i] = logTable_.data() + static_cast<std::size_t>(cells[i]) * C;
        weights[i] = static_cast<double>(counts[i]);
    }
    accumulateRows(rows.data(), weights.data(), distinct, C, out);
}

double HistogramClassifier::screeningBound(const Tap& tap) const {
    const auto samples = static_cast<double>(tap.samples.size());
    return screenStep_ * samples + 2e-12 * samples * maxAbsLog_;
}

void HistogramClassifier::perceptScores(const Tap& tap, double* out) const {
    screenedScores(tap, kPerceptMarginNats, true, out);
}

int HistogramClassifier::screenedScores(const Tap& tap, double marginNats, bool posterior,
                                        double* out) const {
    const std::size_t C = static_cast<std::size_t>(classes_);
    if (tap.samples.size() > kMaxScreenSamples) {
        logLikelihoods(tap, out);
        return -1;
    }
    const std::uint32_t* cells = nullptr;
    const std::int32_t* counts = nullptr;
    const std::size_t distinct = tapCells(tap, &cells, &counts);
    thread_local std::vector<std::int32_t> sums;
    sums.resize(screenStride_);
    detail::screenSums(screenTable_.data(), screenStride_, cells, counts, distinct, sums.data(),
                       false);
    // A screening score is base + step * sum, the base (the counts times the cells' offsets)
    // common to every class. Each level is within half a step of its entry, so a score is within
    // step/2 per sample of the exact one, plus the rounding of the double sums (far below 1e-12
    // of the terms' magnitudes, at most samples * max |log P|); the bound takes twice both.
    const auto samples = static_cast<double>(tap.samples.size());
    const double bound = screeningBound(tap);
    // Classes that could be within `marginNats` of the exact maximum, or of a tie with it, are
    // those whose screening score is within twice the bound, the margin and a tie's width (of
    // the largest magnitude a score can have) of the best: counted in levels, rounded up.
    const double magnitude = samples * maxAbsLog_ + bound;
    const double reach = std::ceil(
        (2.0 * bound + marginNats + 2.0 * kTieTolerance * (magnitude + bound + 1.0)) / screenStep_ +
        1.0);
    if (!(reach < 1e9)) {
        logLikelihoods(tap, out);
        return -1;
    }
    const ScreenLead lead = screenLead(sums.data(), C, static_cast<std::int64_t>(reach));
    const std::int32_t floor = lead.floor;
    // One class alone within the margin is the maximum, and no other ties with it.
    if (lead.within == 1 && !posterior) return lead.first;
    // The rest cannot decide anything: for a posterior they keep their screening scores (each
    // adds at most e^-margin to its normaliser), otherwise they are out.
    if (posterior) {
        double base = 0.0;
        for (std::size_t i = 0; i < distinct; ++i)
            base += static_cast<double>(counts[i]) * screenOffset_[cells[i]];
        for (std::size_t c = 0; c < C; ++c)
            out[c] = base + screenStep_ * static_cast<double>(sums[c]);
    } else {
        std::fill(out, out + C, -std::numeric_limits<double>::infinity());
    }
    // The classes within are summed exactly, in the same order and operations as
    // logLikelihoods().
    thread_local std::vector<std::size_t> within;
    within.clear();
    for (std::size_t c = 0; c < C; ++c)
        if (sums[c] >= floor) within.push_back(c);
    exactSums(within.data(), within.size(), cells, counts, distinct, out);
    return -1;
}

}  // namespace activetouch
