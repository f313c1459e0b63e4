#pragma once
// Deterministic random numbers, identical on every platform and standard library: the simulated
// rig promises bit-identical taps for a seed, which std::normal_distribution does not guarantee.
#include <cmath>
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

    /// Standard normal (Marsaglia polar method).
    double normal() {
        if (hasSpareNormal_) {
            hasSpareNormal_ = false;
            return spareNormal_;
        }
        double u, v, s;
        do {
            u = 2.0 * uniform() - 1.0;
            v = 2.0 * uniform() - 1.0;
            s = u * u + v * v;
        } while (s >= 1.0 || s == 0.0);
        const double f = std::sqrt(-2.0 * std::log(s) / s);
        spareNormal_ = v * f;
        hasSpareNormal_ = true;
        return u * f;
    }

    double normal(double mean, double sigma) { return mean + sigma * normal(); }

    /// `count` standard normals into `out`, for the simulated rig's per-sample effects: the
    /// ziggurat method (128 layers, one 64-bit draw for nearly every value, exact in
    /// distribution), several times faster than normal(). A separate sequence from normal()'s:
    /// the two are not interchangeable for a given seed.
    void normals(double* out, std::size_t count);

private:
    /// The ziggurat's value for a draw outside its layer's inner rectangle (the wedge or the
    /// tail), drawing further as it needs.
    double zigguratSlow(std::uint64_t bits);
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t state_[4]{};
    bool hasSpareNormal_ = false;
    double spareNormal_ = 0.0;
};

}  // namespace activetouch
