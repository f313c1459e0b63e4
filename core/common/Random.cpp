#include "core/common/Random.h"

#include <algorithm>
#include <bit>

#include "core/common/Avx2Clones.h"

namespace activetouch {
namespace {

/// The polar method's second half for `n` accepted pairs: f = sqrt(-2 log s / s) and the pair
/// (u f, v f), in the order normal() gives them. Cloned for AVX2 (no FMA: neither clone fuses a
/// product into a sum), both giving normal()'s very bits.
ACTIVETOUCH_AVX2_CLONES void polarFinish(const double* __restrict u, const double* __restrict v,
                                         const double* __restrict s, std::size_t n,
                                         double* __restrict out) {
    for (std::size_t j = 0; j < n; ++j) {
        const double f = std::sqrt(-2.0 * RandomStream::logOfPositive(s[j]) / s[j]);
        out[2 * j] = u[j] * f;
        out[2 * j + 1] = v[j] * f;
    }
}

}  // namespace

void RandomStream::normals(double* out, std::size_t count) {
    std::size_t at = 0;
    if (count > 0 && hasSpareNormal_) {
        out[at++] = spareNormal_;
        hasSpareNormal_ = false;
    }
    constexpr std::size_t kBlock = 128;
    double u[kBlock], v[kBlock], s[kBlock], pairs[2 * kBlock];
    while (at < count) {
        const std::size_t wanted = std::min(kBlock, (count - at + 1) / 2);
        // Candidates drawn as normal() draws them, each written in place and kept (the count
        // moved on) only if inside the unit disc: no branch on the rejection, and no draw past
        // the pair normal() would stop at. Then the logarithms and the roots, several to an
        // instruction.
        std::size_t m = 0;
        while (m < wanted) {
            // 2 uniform() - 1 as (x >> 11) 2^-52 - 1: the same exact value in one product.
            const double a = static_cast<double>(next() >> 11) * 0x1.0p-52 - 1.0;
            const double b = static_cast<double>(next() >> 11) * 0x1.0p-52 - 1.0;
            const double r = a * a + b * b;
            u[m] = a;
            v[m] = b;
            s[m] = r;
            // 0 < r < 1 (a sum of squares is never negative nor NaN): its bits less one below
            // those of 1 less one, as unsigned integers.
            m += std::bit_cast<std::uint64_t>(r) - 1u < 0x3FEFFFFFFFFFFFFFull;
        }
        polarFinish(u, v, s, m, pairs);
        const std::size_t take = std::min(2 * m, count - at);
        std::copy(pairs, pairs + take, out + at);
        at += take;
        if (take < 2 * m) {  // an odd count: the last pair's second value is kept, as normal() does
            spareNormal_ = pairs[2 * m - 1];
            hasSpareNormal_ = true;
        }
    }
}

}  // namespace activetouch
