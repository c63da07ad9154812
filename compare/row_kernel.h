// What the metrics' per-pixel row loops share: the clone attribute that compiles a row kernel
// for AVX2 and for any x86-64, and powers in plain arithmetic that vectorise.
#pragma once

#include <bit>
#include <cstdint>
#include <numbers>

// A row kernel is compiled twice, for AVX2 and for any x86-64, and picked at load time. Both
// clones do the same element-wise operations in the same order (no FMA), so the result does
// not depend on the CPU. (Define TWINRENDER_ROW_KERNEL empty to build without the clones.)
#if !defined(TWINRENDER_ROW_KERNEL)
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define TWINRENDER_ROW_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define TWINRENDER_ROW_KERNEL
#endif
#endif

namespace twinrender::compare::rowmath {

// Powers (the sRGB curve, ꟻLIP's ^qc and ^(1 - feature difference)) in plain arithmetic, so
// that the row loops vectorise: libm's powf was half of ꟻLIP's time. Double precision
// throughout; relative error below 1e-10, so the float results are powf's to the last bit or
// one off.

constexpr double TWO_52 = 4503599627370496.0;  // 2^52: adding it rounds a double to an integer

// log2 of a positive normal double: x = m 2^e, m in [sqrt(1/2), sqrt(2)), and
// ln m = 2 atanh(s) = 2 (s + s^3/3 + ...), s = (m - 1) / (m + 1), |s| < 0.172 (13th power:
// error < 2e-11).
inline double log2Positive(double x) {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
    // The biased exponent as a double, without an int -> double conversion: 2^52 + k - 2^52.
    const double e0 =
        std::bit_cast<double>((bits >> 52) | 0x4330000000000000ull) - (TWO_52 + 1023.0);
    const double m0 = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
    // Selects between values computed on both sides (a conditional add would not vectorise).
    const double e1 = e0 + 1.0, m1 = 0.5 * m0;
    const bool high = m0 > std::numbers::sqrt2;
    const double e = high ? e1 : e0;
    const double m = high ? m1 : m0;
    const double s = (m - 1.0) / (m + 1.0);
    const double s2 = s * s;
    const double series =
        1.0 + s2 * (1.0 / 3 +
                    s2 * (1.0 / 5 + s2 * (1.0 / 7 + s2 * (1.0 / 9 + s2 * (1.0 / 11 + s2 / 13)))));
    return e + 2.0 * std::numbers::log2e * s * series;
}

// 2^t for t in [-1000, 1000]: 2^n with n = round(t) built in the exponent bits, times
// e^(f ln 2), f = t - n in [-0.5, 0.5], by its Taylor series to degree 10 (error < 3e-13).
inline double exp2Bounded(double t) {
    const double n = (t + 1.5 * TWO_52) - 1.5 * TWO_52;  // round to nearest, |t| < 2^51
    const double z = (t - n) * std::numbers::ln2;
    const double p =
        1.0 +
        z * (1.0 +
             z * (1.0 / 2 +
                  z * (1.0 / 6 +
                       z * (1.0 / 24 +
                            z * (1.0 / 120 +
                                 z * (1.0 / 720 + z * (1.0 / 5040 +
                                                       z * (1.0 / 40320 + z * (1.0 / 362880 +
                                                                               z / 3628800)))))))));
    const std::uint64_t biased =
        std::bit_cast<std::uint64_t>(n + (TWO_52 + 1023.0)) & 0xFFFFFFFFFFFFFull;
    return p * std::bit_cast<double>(biased << 52);
}

// x^e for x >= 0 (0 for x = 0) and |e log2 x| < 1000.
inline float powNonNegative(float x, float e) {
    const double r = exp2Bounded(e * log2Positive(x > 0.0f ? x : 1.0f));
    return x > 0.0f ? static_cast<float>(r) : 0.0f;
}

}  // namespace twinrender::compare::rowmath
