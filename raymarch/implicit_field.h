// The colour field along one ray and its first crossing of the surface level.
//
// phi(x) = sum_j v_j W(|x - x_j|, h_j) (DESIGN.md), W the M4 spline. Along a ray
// x(t) = o + t d, particle j contributes f_j(t) = c_j w(sqrt((t - tc_j)^2 + d2_j) / h_j) with
// c_j = v_j / (pi h_j^3), tc_j its closest-approach parameter and d2_j its squared distance
// from the ray; it is non-zero only on its support interval (t0_j, t1_j).
//
// The root finder never steps over a crossing. Along a line, f_j'' = w''(q) (dq/dt)^2 +
// w'(q) d2q/dt2 / h... and the second term is <= 0 (w' <= 0, q convex in t), so f_j'' <=
// c_j max(w''(q), 0) (dq/dt)^2 with max(w'', 0) <= 1.5 (and <= 1.5 (2 - q) for q >= 1) and
// (dq/dt)^2 <= (1 - d2/(4 h^2)) / h^2 inside the support. With M the sum of those bounds
// over the window ahead, phi(a + s) <= phi(a) + phi'(a) s + M s^2 / 2. The step is the smallest s at
// which that upper bound reaches the level: it cannot pass the first root, it grows far from
// the surface and it becomes a Newton step from below close to it (quadratic convergence).
#pragma once

#include <cstdint>
#include <vector>

namespace twinrender::raymarch {

struct Candidate {
    double tc;    // ray parameter of the closest approach to the particle
    double d2;    // squared distance of the particle from the ray line
    double t0;    // support interval (t0, t1) on the ray
    double t1;
    double coef;  // v / (pi h^3)
    double invH;  // 1 / h
    double peak;  // the largest contribution along the ray: coef * w(sqrt(d2) / h)
    std::uint32_t index;
};

// Builds the candidate of a particle at `center` for a ray (origin, unit direction); returns
// false when the ray line misses its support sphere.
bool makeCandidate(const double origin[3], const double direction[3], const double center[3],
                   double h, double volume, std::uint32_t index, Candidate& out);

struct FieldSample {
    double value = 0.0;      // phi(t)
    double slope = 0.0;      // dphi/dt
    double curvature = 0.0;  // M: upper bound of d2phi/dt2 over the window
};

// The candidates of one ray segment in the layout the field loops want: structure of arrays,
// float, ray parameters relative to `base` (the segment start), so float keeps about 1e-7 of
// the segment's own scale wherever the segment lies. The loops are vectorised with a fixed
// lane order, so results do not depend on the thread that runs them.
class RayField {
public:
    // `candidates`: in any fixed order (it is the summation order). `base`: a ray parameter
    // near the segment.
    void assign(const std::vector<Candidate>& candidates, double base);
    std::size_t size() const { return mT0.size(); }
    double base() const { return mBase; }

    // phi, dphi/dt at t and the curvature bound over [t, t + window].
    FieldSample sample(double t, double window) const;
    // An upper bound of phi on [t, tEnd]: each particle at its largest value there (its peak
    // when the closest approach lies ahead, its value at t when it lies behind).
    double remainingBound(double t, double tEnd) const;

private:
    double mBase = 0.0;
    std::vector<float> mTc, mD2, mT0, mT1, mCoef, mIh2, mPeak;
};

struct Crossing {
    enum class Status {
        Hit,          // the first crossing is at t (phi(tBelow) < level <= phi(tBelow + tol))
        Miss,         // phi < level on the whole interval
        Inside,       // phi >= level already at the start
        Unresolved,   // iteration limit reached (grazing a tangency): counted, never dropped
    };
    Status status = Status::Miss;
    double t = 0.0;       // the crossing, interpolated inside [tBelow, tBelow + tolerance]
    double tBelow = 0.0;  // the last point known below the level (a safe ray origin)
    int evaluations = 0;
};

struct CrossingSettings {
    double level = 0.13;       // surface level of phi
    double tolerance = 1e-4;   // absolute, along t (the caller passes 1e-4 h)
    double maxStep = 1.0;      // the window over which the curvature bound is taken
    int maxIterations = 256;
};

// The first t in [ta, tb] where phi reaches the level. `field` must hold every particle whose
// support overlaps [ta, tb] (others may be there too).
Crossing findFirstCrossing(const RayField& field, double ta, double tb,
                           const CrossingSettings& settings);

}  // namespace twinrender::raymarch
