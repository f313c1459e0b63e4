#include "core/common/Random.h"

#include <algorithm>
#include <array>
#include <bit>

#include "core/common/Avx2Clones.h"

namespace activetouch {
namespace {

// The ziggurat for the standard normal density f(x) = exp(-x^2/2) (unnormalised): 128 layers of
// equal area v, the base layer a rectangle of width x[0] = v / f(r) standing for the strip under
// f up to r plus the tail beyond it. Layer i spans heights f(x[i])..f(x[i+1]) and widths 0..x[i];
// its part left of x[i+1] lies wholly under f. The constants r and v are those that close the
// stack at x[128] = 0 (Marsaglia and Tsang's for 128 layers).
constexpr int kLayers = 128;
constexpr double kR = 3.442619855899;
constexpr double kV = 9.91256303526217e-3;

struct Ziggurat {
    std::array<double, kLayers + 1> x{}, f{};
    std::array<double, kLayers> inner{};  // x[i+1] / x[i]: a draw below it is accepted at once
    Ziggurat() {
        auto density = [](double t) { return std::exp(-0.5 * t * t); };
        x[0] = kV / density(kR);
        x[1] = kR;
        for (int i = 1; i < kLayers - 1; ++i)
            x[i + 1] = std::sqrt(-2.0 * std::log(kV / x[i] + density(x[i])));
        x[kLayers] = 0.0;
        for (int i = 0; i <= kLayers; ++i) f[i] = density(x[i]);
        for (int i = 0; i < kLayers; ++i) inner[i] = x[i + 1] / x[i];
    }
};

const Ziggurat& ziggurat() {
    static const Ziggurat z;
    return z;
}

}  // namespace

namespace {

/// A value with the sign bit of `sign` (0 or 1 << 63) flipped in, without a branch: the sign is
/// random, so a branch on it would be mispredicted half the time.
double withSign(double v, std::uint64_t sign) {
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(v) ^ sign);
}

// Each draw's value where it falls in its layer's inner rectangle (the layer from the low 7
// bits, the sign from the 8th, a uniform in [0, 1) from the top 53); the places of those that do
// not (about 1 in 80) listed in `outside`, their count returned. Cloned for AVX2 (gathering the
// layers' widths), the same values in either clone.
ACTIVETOUCH_AVX2_CLONES std::size_t zigguratFast(const Ziggurat& z, const std::uint64_t* bits,
                                                 std::size_t n, double* out,
                                                 std::uint16_t* outside) {
    std::size_t m = 0;
    for (std::size_t j = 0; j < n; ++j) {
        const auto i = static_cast<std::size_t>(bits[j] & (kLayers - 1));
        const double u = static_cast<double>(static_cast<std::int64_t>(bits[j] >> 11)) * 0x1.0p-53;
        out[j] = withSign(u * z.x[i], (bits[j] & kLayers) << 56);
        outside[m] = static_cast<std::uint16_t>(j);
        m += u < z.inner[i] ? 0 : 1;
    }
    return m;
}

}  // namespace

double RandomStream::zigguratSlow(std::uint64_t bits) {
    const Ziggurat& z = ziggurat();
    for (;;) {
        const int i = static_cast<int>(bits & (kLayers - 1));
        const std::uint64_t sign = (bits & kLayers) << 56;
        const double u = static_cast<double>(static_cast<std::int64_t>(bits >> 11)) * 0x1.0p-53;
        const double x = u * z.x[static_cast<std::size_t>(i)];
        if (u < z.inner[static_cast<std::size_t>(i)]) return withSign(x, sign);
        if (i == 0) {  // beyond r: Marsaglia's exponential rejection for the normal tail
            double a, b;
            do {
                a = -std::log(1.0 - uniform()) / kR;
                b = -std::log(1.0 - uniform());
            } while (b + b < a * a);
            return withSign(kR + a, sign);
        }
        // The wedge between x[i+1] and x[i]: under the curve with the density's probability.
        const auto k = static_cast<std::size_t>(i);
        const double y = z.f[k] + uniform() * (z.f[k + 1] - z.f[k]);
        if (y < std::exp(-0.5 * x * x)) return withSign(x, sign);
        bits = next();
    }
}

void RandomStream::normals(double* out, std::size_t count) {
    // In blocks: the block's 64-bit draws first (the generator's own dependency chain alone),
    // then each value from its draw - the layer from the low 7 bits, the sign from the 8th, a
    // uniform in [0, 1) from the top 53 - accepted at once unless it falls outside its layer's
    // inner rectangle (about 1 in 80); those few are finished last, drawing further.
    const Ziggurat& z = ziggurat();
    constexpr std::size_t kBlock = 256;
    std::uint64_t bits[kBlock];
    for (std::size_t at = 0; at < count; at += kBlock) {
        const std::size_t n = std::min(kBlock, count - at);
        for (std::size_t j = 0; j < n; ++j) bits[j] = next();
        double* o = out + at;
        std::uint16_t outside[kBlock];  // the block's draws outside their inner rectangles
        const std::size_t m = zigguratFast(z, bits, n, o, outside);
        for (std::size_t r = 0; r < m; ++r) o[outside[r]] = zigguratSlow(bits[outside[r]]);
    }
}

}  // namespace activetouch
