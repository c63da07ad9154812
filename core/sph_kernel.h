// The M4 cubic spline kernel (Monaghan & Lattanzio 1985) in 3-D with support radius 2h,
// as OpenSPH uses it: W(r, h) = 1/(pi h^3) * w(q), q = r/h,
//   w(q) = 1 - 1.5 q^2 + 0.75 q^3   for 0 <= q < 1
//        = 0.25 (2 - q)^3            for 1 <= q < 2
//        = 0                          otherwise.
#pragma once

#include <cmath>
#include <numbers>

namespace twinrender::core {

constexpr double M4_SUPPORT = 2.0;  // support radius in units of h

// w(q) for q in [0, 2], as one select between the two pieces (no branch on the support): the
// form of vector loops, which clamp q to 2 (beyond 2 this is not 0).
template <typename T>
constexpr T m4ShapeInSupport(T q) {
    const T a = T(2) - q;
    return q < T(1) ? T(1) - T(1.5) * q * q + T(0.75) * q * q * q : T(0.25) * a * a * a;
}

// w(q), without the 1/(pi h^3) normalisation.
template <typename T>
constexpr T m4Shape(T q) {
    return q < T(2) ? m4ShapeInSupport(q) : T(0);
}

// dw/dq.
template <typename T>
constexpr T m4ShapeDerivative(T q) {
    if (q < T(1)) return T(-3) * q + T(2.25) * q * q;
    if (q < T(2)) {
        const T a = T(2) - q;
        return T(-0.75) * a * a;
    }
    return T(0);
}

// w'(q) / q for q in [0, 2], as one select between the two pieces: the factor of the
// gradient, grad w(|r| / h) = (w'(q) / q) r / h^2. The inner piece needs no division, so it
// stays finite at q = 0.
template <typename T>
constexpr T m4ShapeDerivativeOverQ(T q) {
    const T a = T(2) - q;
    return q < T(1) ? T(-3) + T(2.25) * q : T(-0.75) * a * a / q;
}

// max(x, 0), exactly, without a comparison (which keeps GCC from vectorising a loop).
template <typename T>
inline T positivePart(T x) {
    return T(0.5) * (x + std::abs(x));
}

// dw/dq as 3 max(1 - q, 0)^2 - 0.75 max(2 - q, 0)^2: no comparison at all, and 0 beyond the
// support (the form of loops that vectorise without special flags).
template <typename T>
inline T m4ShapeDerivativeBranchFree(T q) {
    const T a = positivePart(T(2) - q);
    const T b = positivePart(T(1) - q);
    return T(3) * b * b - T(0.75) * a * a;
}

// d2w/dq2 (continuous; undefined at q = 0 only as a limit of the 3-D Hessian, see
// core::colourFieldDerivatives, which skips r = 0).
template <typename T>
constexpr T m4ShapeSecondDerivative(T q) {
    if (q < T(1)) return T(-3) + T(4.5) * q;
    if (q < T(2)) return T(1.5) * (T(2) - q);
    return T(0);
}

template <typename T>
constexpr T m4Kernel(T r, T h) {
    return m4Shape(r / h) / (std::numbers::pi_v<T> * h * h * h);
}

// dW/dr.
template <typename T>
constexpr T m4KernelDerivative(T r, T h) {
    return m4ShapeDerivative(r / h) / (std::numbers::pi_v<T> * h * h * h * h);
}

// OpenSPH's volume cap for the colour field: v = m / rho, at most 0.1 * (4/3) pi h^3
// (also the volume used when mass or density are unknown).
template <typename T>
constexpr T maxParticleVolume(T h) {
    return T(0.1) * T(4) / T(3) * std::numbers::pi_v<T> * h * h * h;
}

}  // namespace twinrender::core
