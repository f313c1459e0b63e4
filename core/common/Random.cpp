#include "core/common/Random.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/common/Avx2Clones.h"

namespace activetouch {

namespace {

/// RandomStream::logOfPositive's body, inlined where a loop runs it several to an instruction.
inline double logOf(double x) {
    constexpr std::uint64_t kRootHalf = 0x3FE6A09E667F3BCDull;
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
    const std::uint64_t shifted = bits - kRootHalf + (1024ull << 52);
    const std::uint64_t biased = shifted >> 52;  // k + 1024
    const double k = std::bit_cast<double>(0x4330000000000000ull | biased) - (0x1p52 + 1024.0);
    const double m = std::bit_cast<double>(bits - (biased << 52) + (1024ull << 52));
    const double f = (m - 1.0) / (m + 1.0);
    const double z = f * f;
    double p = 2.0 / 21;
    p = 2.0 / 19 + z * p;
    p = 2.0 / 17 + z * p;
    p = 2.0 / 15 + z * p;
    p = 2.0 / 13 + z * p;
    p = 2.0 / 11 + z * p;
    p = 2.0 / 9 + z * p;
    p = 2.0 / 7 + z * p;
    p = 2.0 / 5 + z * p;
    p = 2.0 / 3 + z * p;
    constexpr double kLn2High = 0x1.62e42fee00000p-1;  // k times it is exact
    constexpr double kLn2Low = 0x1.a39ef35793c76p-33;
    return (k * kLn2High + 2.0 * f) + (k * kLn2Low + f * (z * p));
}

// The polar method's steps, each written once for normal() and normals().

/// A coordinate of a candidate, 2 uniform() - 1 from a 64-bit draw: (x >> 11) 2^-52 - 1, the same
/// exact value in one product.
double centred(std::uint64_t x) {
    return static_cast<double>(x >> 11) * 0x1.0p-52 - 1.0;
}

/// Whether a candidate's squared radius is inside the unit disc and not 0: for a sum of squares
/// (never negative nor NaN), its bits less one below those of 1 less one, as unsigned integers,
/// with no branch.
bool insideDisc(double s) {
    return std::bit_cast<std::uint64_t>(s) - 1u < 0x3FEFFFFFFFFFFFFFull;
}

/// The factor that turns an accepted candidate (u, v) with squared radius s into two normals.
double polarScale(double s) {
    return std::sqrt(-2.0 * logOf(s) / s);
}

/// The polar method's second half for `n` accepted pairs, in the order normal() gives them.
/// Cloned for AVX2 (no FMA: neither clone fuses a product into a sum), both giving normal()'s
/// very bits.
ACTIVETOUCH_AVX2_CLONES void polarFinish(const double* __restrict u, const double* __restrict v,
                                         const double* __restrict s, std::size_t n,
                                         double* __restrict out) {
    for (std::size_t j = 0; j < n; ++j) {
        const double f = polarScale(s[j]);
        out[2 * j] = u[j] * f;
        out[2 * j + 1] = v[j] * f;
    }
}

}  // namespace

double RandomStream::logOfPositive(double x) {
    return logOf(x);
}

double RandomStream::normal() {
    if (hasSpareNormal_) {
        hasSpareNormal_ = false;
        return spareNormal_;
    }
    double u, v, s;
    do {
        u = centred(next());
        v = centred(next());
        s = u * u + v * v;
    } while (!insideDisc(s));
    const double f = polarScale(s);
    spareNormal_ = v * f;
    hasSpareNormal_ = true;
    return u * f;
}

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
            const double a = centred(next()), b = centred(next());
            const double r = a * a + b * b;
            u[m] = a;
            v[m] = b;
            s[m] = r;
            m += insideDisc(r);
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
