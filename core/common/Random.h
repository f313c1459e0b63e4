#pragma once
// Deterministic random numbers, identical on every platform and standard library: the simulated
// rig promises bit-identical taps for a seed, which std::normal_distribution does not guarantee.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace activetouch {

/// xoshiro256** seeded through splitmix64.
class RandomStream {
public:
    explicit RandomStream(std::uint64_t seed = 0) { reseed(seed); }

    /// A stream for a named purpose: the same seed and name always give the same numbers, and
    /// adding one consumer never shifts the numbers another consumer sees.
    static RandomStream derived(std::uint64_t seed, std::string_view purpose) {
        std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the purpose
        for (char c : purpose) {
            h ^= static_cast<unsigned char>(c);
            h *= 1099511628211ull;
        }
        return RandomStream(seed ^ (h * 0x9E3779B97F4A7C15ull));
    }

    void reseed(std::uint64_t seed) {
        for (auto& s : state_) {
            seed += 0x9E3779B97F4A7C15ull;
            std::uint64_t z = seed;
            z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
            z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
            s = z ^ (z >> 31);
        }
        hasSpareNormal_ = false;
    }

    std::uint64_t next() {
        const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
        const std::uint64_t t = state_[1] << 17;
        state_[2] ^= state_[0];
        state_[3] ^= state_[1];
        state_[1] ^= state_[2];
        state_[0] ^= state_[3];
        state_[2] ^= t;
        state_[3] = rotl(state_[3], 45);
        return result;
    }

    /// Uniform in [0, 1).
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

    /// Uniform in [lo, hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

    /// Standard normal (Marsaglia's polar method, its logarithm logOfPositive()).
    double normal();

    double normal(double mean, double sigma) { return mean + sigma * normal(); }

    /// `count` standard normals into `out`: the very values `count` calls of normal() give, the
    /// stream left as they leave it, made in blocks (the draws, then the logarithms and roots
    /// several to an instruction) for the simulated rig's per-sample effects.
    void normals(double* out, std::size_t count);

    /// The natural logarithm of a positive normal double, within two units in the last place,
    /// in the same operations on every machine and library (no call to the C library's log,
    /// whose last bits differ from one library to another), and inlined so that a loop of them
    /// runs several to an instruction. ln m for m = x 2^-k in [sqrt(1/2), sqrt(2)) is
    /// 2 atanh(f), f = (m - 1) / (m + 1), |f| <= 0.172: the odd series to f^21 (the next term is
    /// below 2^-55 of the sum), plus k ln 2 in two parts.
    static double logOfPositive(double x);

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t state_[4]{};
    bool hasSpareNormal_ = false;
    double spareNormal_ = 0.0;
};

}  // namespace activetouch
