// phi and dphi/dt at a point of a ray field (ray_field.h), and the bounds of d2phi/dt2 over a
// window ahead of it that let the root search step without passing a crossing.
//
// With delta = sqrt(d2) / h, the second derivative of a particle's term is exactly
// f'' = c F(q) / h^2 with
//   F(q) = -3 + 4.5 q - 2.25 delta^2 / q                       for q < 1,
//   F(q) = (2 - q) (1.5 - delta^2 (1.5 + 0.75 q) / q^3)        for 1 <= q < 2,
// increasing on q < 1, and 0 beyond the support. Over a window of the ray, where q_j spans
// [qmin, qmax], it is bounded above by (delta <= q, and 2 - q <= (4 - q^2) / 3 on [1, 2])
//   -0.75 + 2.25 (qmax^2 - delta^2)              when qmax <= 1,
//   1.5 (1 - delta^2 / qmax^2)                   when qmin < 1 < qmax,
//   0.5 (4 - qmin^2) (1 - delta^2 / qmax^2)      when qmin >= 1,
// and below by -3 (q < 1) or -0.75 (q >= 1). With M and m the sums of those bounds,
//   phi(a) + phi'(a) s + m s^2 / 2 <= phi(a + s) <= phi(a) + phi'(a) s + M s^2 / 2
// for every s in the window.
#pragma once

#include "raymarch/ray_field.h"

namespace twinrender::raymarch {

struct FieldSample {
    double value = 0.0;         // phi(t)
    double slope = 0.0;         // dphi/dt
    double curvature = 0.0;     // M: upper bound of d2phi/dt2 over the window
    double curvatureLow = 0.0;  // m: lower bound of d2phi/dt2 over the window
    double ahead = 0.0;         // upper bound of phi over [t, t + horizon]
};

// phi, dphi/dt at t, the curvature bounds over [t, t + window] and the bound of phi over
// [t, t + horizon]: each particle at its largest value there (its peak when the closest
// approach lies ahead, its value at t when it lies behind).
FieldSample sampleField(const RayField& field, double t, double window, double horizon = 0.0);
// phi and dphi/dt at t only (a third of the work).
FieldSample sampleValue(const RayField& field, double t);

}  // namespace twinrender::raymarch
