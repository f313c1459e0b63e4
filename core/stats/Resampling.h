#pragma once
// The generator bootstrap resampling draws from: a 64-bit linear congruential generator with
// Knuth's MMIX constants, its upper 31 bits taken, from a fixed seed, so that every machine draws
// the same resamples and prints the same intervals. Not for anything a simulation draws.
#include <cstddef>
#include <cstdint>

namespace activetouch::stats {

class ResamplingGenerator {
public:
    explicit ResamplingGenerator(std::uint64_t seed) : state_(seed) {}
    /// A draw in 0..n-1 (n > 0).
    std::size_t below(std::size_t n) {
        state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<std::size_t>((state_ >> 33) % n);
    }

private:
    std::uint64_t state_;
};

}  // namespace activetouch::stats
