// The M4 cubic spline kernel (Monaghan & Lattanzio 1985) in 3-D with support radius 2h,
// as OpenSPH uses it: W(r, h) = 1/(pi h^3) * w(q), q = r/h,
//   w(q) = 1 - 1.5 q^2 + 0.75 q^3   for 0 <= q < 1
//        = 0.25 (2 - q)^3            for 1 <= q < 2
//        = 0                          otherwise.
#pragma once

#include <numbers>

namespace twinrender::core {

constexpr double M4_SUPPORT = 2.0;  // support radius in units of h

// w(q), without the 1/(pi h^3) normalisation.
template <typename T>
constexpr T m4Shape(T q) {
    if (q < T(1)) return T(1) - T(1.5) * q * q + T(0.75) * q * q * q;
    if (q < T(2)) {
        const T a = T(2) - q;
        return T(0.25) * a * a * a;
    }
    return T(0);
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
