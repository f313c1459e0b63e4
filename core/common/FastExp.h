#pragma once
// e^x for the sums of exponentials the classifier's posteriors are made of (log-sum-exp, the
// continuous percept's weights): written without branches or library calls, so that a loop over
// classes runs several to an instruction, and without FMA, so that every build gives the same
// bits. Within 2 ulp of e^x over its domain [-708, 0] (tests/core/test_random.cpp holds it).
#include <bit>
#include <cstdint>

namespace activetouch {

/// The lower end of expNonPositive's domain: e^-708 is the smallest power of e above the least
/// normal double. Beside a sum of at least 1 (the largest term of a log-sum-exp is e^0), a term
/// below it is lost in rounding, so a sum may leave such terms out.
inline constexpr double kExpFloor = -708.0;

/// e^x for x in [kExpFloor, 0]; x is clamped into that range first (a NaN reads as kExpFloor).
inline double expNonPositive(double x) {
    x = x > kExpFloor ? x : kExpFloor;
    x = x < 0.0 ? x : 0.0;
    // x = n ln 2 + r with n a whole number and |r| <= ln 2 / 2: n by rounding x / ln 2 with the
    // 1.5 * 2^52 shift (the sum has no fraction bits, and its low bits are n), ln 2 in two parts
    // so that n ln 2 is exact to 2^-80.
    constexpr double kShift = 0x1.8p52;
    const double shifted = x * 1.4426950408889634 + kShift;
    const double n = shifted - kShift;
    const double r = (x - n * 0x1.62e42fee00000p-1) - n * 0x1.a39ef35793c76p-33;
    // e^r by its Taylor series to r^13 (the rest under 2^-57 of it for |r| <= 0.347).
    double p = 1.0 / 6227020800.0;
    p = p * r + 1.0 / 479001600.0;
    p = p * r + 1.0 / 39916800.0;
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    // 2^n from n's bits (n in [-1022, 0]: a normal double).
    const std::uint64_t nBits = std::bit_cast<std::uint64_t>(shifted);
    const double scale = std::bit_cast<double>((nBits + 1023) << 52);
    return p * scale;
}

}  // namespace activetouch
