#include "raymarch/implicit_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/sph_kernel.h"

namespace twinrender::raymarch {

using core::m4Shape;
using core::m4ShapeDerivative;

// Upper bound of w''(q) along a line, see the header.
constexpr double W_CURVATURE_BOUND = 1.5;

bool makeCandidate(const double origin[3], const double direction[3], const double center[3],
                   double h, double volume, std::uint32_t index, Candidate& out) {
    const double w[3] = {center[0] - origin[0], center[1] - origin[1], center[2] - origin[2]};
    const double tc = w[0] * direction[0] + w[1] * direction[1] + w[2] * direction[2];
    // Perpendicular offset computed directly (not |w|^2 - tc^2), which cancels far away.
    const double p[3] = {w[0] - tc * direction[0], w[1] - tc * direction[1], w[2] - tc * direction[2]};
    const double d2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    const double support = core::M4_SUPPORT * h;
    const double chord2 = support * support - d2;
    if (chord2 <= 0.0) return false;
    const double half = std::sqrt(chord2);
    out.tc = tc;
    out.d2 = d2;
    out.t0 = tc - half;
    out.t1 = tc + half;
    out.invH = 1.0 / h;
    out.coef = volume / (std::numbers::pi * h * h * h);
    out.peak = out.coef * m4Shape(std::sqrt(d2) * out.invH);
    out.index = index;
    return true;
}

FieldSample sampleField(const std::vector<Candidate>& candidates, double t, double window) {
    FieldSample s;
    const double tEnd = t + window;
    for (const Candidate& c : candidates) {
        if (c.t0 >= tEnd) break;  // sorted by t0: nothing later reaches the window
        if (c.t1 <= t) continue;
        const double ih2 = c.invH * c.invH;
        // Closest approach within the window, for the curvature bound.
        const double tNear = std::clamp(c.tc, t, tEnd) - c.tc;
        const double qNear2 = (tNear * tNear + c.d2) * ih2;
        // max(w'', 0) <= 1.5 for q <= 1 and 1.5 (2 - q) beyond; (dq/dt)^2 <= (1 - d2/(4h^2))/h^2.
        const double wBound = qNear2 <= 1.0 ? W_CURVATURE_BOUND
                                            : W_CURVATURE_BOUND * (2.0 - std::sqrt(qNear2));
        s.curvature += c.coef * wBound * std::max(0.0, 1.0 - 0.25 * c.d2 * ih2) * ih2;
        const double dt = t - c.tc;
        const double q2 = (dt * dt + c.d2) * ih2;
        if (q2 >= 4.0) continue;
        const double q = std::sqrt(q2);
        s.value += c.coef * m4Shape(q);
        // d/dt w(q) = w'(q) dq/dt, dq/dt = dt / (r h) = dt / (q h^2).
        if (q > 0.0) s.slope += c.coef * m4ShapeDerivative(q) * dt * ih2 / q;
    }
    return s;
}

double remainingBound(const std::vector<Candidate>& candidates, double t, double tEnd) {
    double bound = 0.0;
    for (const Candidate& c : candidates) {
        if (c.t0 >= tEnd) break;
        if (c.t1 <= t) continue;
        if (c.tc >= t) {
            bound += c.peak;
        } else {
            const double dt = t - c.tc;
            const double q2 = (dt * dt + c.d2) * c.invH * c.invH;
            if (q2 < 4.0) bound += c.coef * m4Shape(std::sqrt(q2));
        }
    }
    return bound;
}

namespace {

// Smallest s >= 0 with value + slope s + curvature s^2 / 2 = level (value < level).
double safeStep(const FieldSample& f, double level) {
    const double gap = level - f.value;
    if (f.curvature > 0.0) {
        const double disc = f.slope * f.slope + 2.0 * f.curvature * gap;
        // Written to avoid cancellation when slope > 0: s = 2 gap / (slope + sqrt(disc)).
        const double root = std::sqrt(disc);
        return f.slope > 0.0 ? 2.0 * gap / (f.slope + root) : (root - f.slope) / f.curvature;
    }
    return f.slope > 0.0 ? gap / f.slope : INFINITY;
}

}  // namespace

Crossing findFirstCrossing(const std::vector<Candidate>& candidates, double ta, double tb,
                           const CrossingSettings& settings) {
    Crossing out;
    const double level = settings.level;
    // Skip ahead: before the k-th support interval opens, phi is at most the sum of the peaks
    // of the particles already entered, so no crossing happens until that sum reaches the level.
    double a = ta;
    {
        double sum = 0.0;
        bool reached = false;
        for (const Candidate& c : candidates) {
            if (c.t1 <= ta) continue;
            sum += c.peak;
            if (sum >= level) {
                a = std::max(ta, c.t0);
                reached = true;
                break;
            }
        }
        if (!reached || a >= tb) {
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
    }
    double previous = a;
    for (int it = 0; it < settings.maxIterations; ++it) {
        const double window = std::min(settings.maxStep, tb - a);
        const FieldSample f = sampleField(candidates, a, window);
        ++out.evaluations;
        if (f.value >= level) {
            // At the start: the ray begins inside. Later the step can only land exactly on the
            // root (the bound touches the level there): a hit.
            out.status = it == 0 ? Crossing::Status::Inside : Crossing::Status::Hit;
            out.t = a;
            out.tBelow = it == 0 ? a : previous;
            return out;
        }
        previous = a;
        // Going away from the surface: stop once nothing ahead can reach the level.
        if (f.slope < 0.0 && remainingBound(candidates, a, tb) < level) {
            ++out.evaluations;
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
        const double step = safeStep(f, level);
        if (step < settings.tolerance) {
            // The bound says the root may be closer than the tolerance: confirm it.
            const double b = a + settings.tolerance;
            const FieldSample fb = sampleField(candidates, b, 0.0);
            ++out.evaluations;
            if (fb.value >= level) {
                const double frac = (level - f.value) / (fb.value - f.value);
                out.status = Crossing::Status::Hit;
                out.tBelow = a;
                out.t = a + settings.tolerance * std::clamp(frac, 0.0, 1.0);
                return out;
            }
            a = b;  // grazing past a tangency; the next step starts below the level
        } else if (step >= window) {
            a += window;
        } else {
            a += step;
        }
        if (a >= tb) {
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
    }
    out.status = Crossing::Status::Unresolved;
    out.tBelow = a;
    return out;
}

}  // namespace twinrender::raymarch
