#pragma once
// e^x for the sums of exponentials the classifier's posteriors are made of (log-sum-exp, the
// continuous percept's weights): written without branches or library calls, so that a loop over
// classes runs several to an instruction, and without FMA, so that every build gives the same
// bits. In double precision within 2 ulp of e^x over its domain [-708, 0]
// (tests/core/test_fast_exp.cpp holds it); in single precision, for weights that need no more,
// within about 2e-7 of it over [-87, 0] at half the work.
#include <bit>
#include <cstdint>
#include <utility>

namespace activetouch {

/// The lower end of expNonPositive's domain: e^-708 is the smallest power of e above the least
/// normal double. Beside a sum of at least 1 (the largest term of a log-sum-exp is e^0), a term
/// below it is lost in rounding, so a sum may leave such terms out.
inline constexpr double kExpFloor = -708.0;

namespace fastexp {

/// What the method needs of a floating-point type: its domain's lower end, the shift that rounds
/// x / ln 2 to a whole number n in its low bits, ln 2 in two parts (n ln 2 exact to far below an
/// ulp), the exponent's bias and place, and the Taylor degree that reaches the type's precision
/// for |r| <= ln 2 / 2.
template <class Real>
struct Traits;

template <>
struct Traits<double> {
    using Bits = std::uint64_t;
    static constexpr double floor = kExpFloor, shift = 0x1.8p52, log2e = 1.4426950408889634;
    static constexpr double ln2Hi = 0x1.62e42fee00000p-1, ln2Lo = 0x1.a39ef35793c76p-33;
    static constexpr Bits bias = 1023;
    static constexpr int mantissa = 52;
    static constexpr std::size_t degree = 13;  // the rest under 2^-57 of e^r for |r| <= 0.347
};

template <>
struct Traits<float> {
    using Bits = std::uint32_t;
    static constexpr float floor = -87.0f, shift = 0x1.8p23f, log2e = 1.44269504f;
    static constexpr float ln2Hi = 0.693359375f, ln2Lo = -2.12194440e-4f;
    static constexpr Bits bias = 127;
    static constexpr int mantissa = 23;
    static constexpr std::size_t degree = 6;  // the rest under 2e-7 of e^r for |r| <= 0.347
};

template <class Real>
constexpr Real factorial(std::size_t k) {
    return k == 0 ? Real(1) : Real(k) * factorial<Real>(k - 1);
}

/// 1 / k!, worked out when compiling.
template <class Real, std::size_t K>
inline constexpr Real kInverseFactorial = Real(1) / factorial<Real>(K);

/// e^r by its Taylor series to r^Degree, in Horner's form, written out term by term.
template <class Real, std::size_t Degree, std::size_t... K>
inline Real taylor(Real r, std::index_sequence<K...>) {
    Real p = kInverseFactorial<Real, Degree>;
    ((p = p * r + kInverseFactorial<Real, Degree - 1 - K>), ...);
    return p;
}

}  // namespace fastexp

/// e^x for x in [Traits<Real>::floor, 0]; x is clamped into that range first (a NaN reads as the
/// floor).
template <class Real>
inline Real expNonPositiveOf(Real x) {
    using T = fastexp::Traits<Real>;
    x = x > T::floor ? x : T::floor;
    x = x < Real(0) ? x : Real(0);
    // x = n ln 2 + r with n a whole number and |r| <= ln 2 / 2: n by rounding x / ln 2 with the
    // 1.5 * 2^mantissa shift (the sum has no fraction bits, and its low bits are n).
    const Real shifted = x * T::log2e + T::shift;
    const Real n = shifted - T::shift;
    const Real r = (x - n * T::ln2Hi) - n * T::ln2Lo;
    const Real p = fastexp::taylor<Real, T::degree>(r, std::make_index_sequence<T::degree>());
    // 2^n from n's bits (n within the exponent's normal range).
    const auto nBits = std::bit_cast<typename T::Bits>(shifted);
    return p * std::bit_cast<Real>((nBits + T::bias) << T::mantissa);
}

/// e^x for x in [kExpFloor, 0] in double precision (within 2 ulp).
inline double expNonPositive(double x) {
    return expNonPositiveOf<double>(x);
}

}  // namespace activetouch
