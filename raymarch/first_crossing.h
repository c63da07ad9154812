// The first crossing of the surface level along a ray field (ray_field.h): the root search.
//
// It never steps over a crossing. With M and m the curvature bounds over a window
// (field_sample.h), phi(a) + phi'(a) s + m s^2 / 2 <= phi(a + s) <= phi(a) + phi'(a) s +
// M s^2 / 2. The step is the smallest s at which the upper bound reaches the level: it
// cannot pass the first root, it grows far from the surface and it becomes a Newton step
// from below close to it (quadratic convergence). The lower bound proves a crossing: once the
// two bounds reach the level within the tolerance of each other, the first root is bracketed
// without another evaluation. Bounds over a window hold over every part of it, so the steps
// that converge on a root inside the window of the last full sample need phi and phi' only.
//
// Before stepping, the search may jump ahead to a hint (a neighbouring ray's crossing): the
// sum over the particles of each one's largest value on [start, hint] (interval_bounds.h)
// bounds phi there, and when it stays below the level no crossing can precede the hint.
#pragma once

#include <cmath>

#include "raymarch/ray_field.h"

namespace twinrender::raymarch {

struct Crossing {
    enum class Status {
        Hit,         // the first crossing is at t (phi(tBelow) < level <= phi(tBelow + tol))
        Miss,        // phi < level on the whole interval
        Inside,      // phi >= level already at the start
        Unresolved,  // iteration limit reached (grazing a tangency): counted, never dropped
    };
    Status status = Status::Miss;
    double t = 0.0;       // the crossing, interpolated inside [tBelow, tBelow + tolerance]
    double tBelow = 0.0;  // the last point known below the level (a safe ray origin)
    int evaluations = 0;
};

struct CrossingSettings {
    double level = 0.13;      // surface level of phi
    double tolerance = 1e-4;  // absolute, along t (the caller passes 1e-4 h)
    double maxStep = 1.0;     // the window over which the curvature bounds are taken
    int maxIterations = 256;
};

// The first t in [ta, tb] where phi reaches the level. `field` must hold every particle whose
// support overlaps [ta, tb] (others may be there too). `hint`, when in (ta, tb), is a guess of
// a point a little before the crossing (a neighbouring ray's): when phi is proven below the
// level on [ta, hint] the search starts there, which skips most of the approach.
Crossing findFirstCrossing(const RayField& field, double ta, double tb,
                           const CrossingSettings& settings, double hint = NAN);

}  // namespace twinrender::raymarch
