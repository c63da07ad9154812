#include "raymarch/first_crossing.h"

#include <algorithm>

#include "raymarch/field_sample.h"
#include "raymarch/interval_bounds.h"
#include "raymarch/vector_loops.h"

namespace twinrender::raymarch {

namespace {

// A bracketed hit's tBelow is taken this fraction of the tolerance before the end of the
// proven-safe step, so that rounding cannot put it on the level.
constexpr double BELOW_MARGIN = 0.01;
// The lower bound is solved for a bracket only once the bracket's estimate, (M - m) step^2 /
// (2 phi'), is within this factor of the tolerance (a square root saved on most steps).
constexpr double BRACKET_ESTIMATE_SLACK = 4.0;
// The bound that lets a search jump to its hint is taken over [ta, hint] in pieces that end
// these fractions of the step window before the hint.
constexpr double HINT_PIECES[] = {0.2, 0.05};

// Smallest s >= 0 at which value + slope s + curvature s^2 / 2 reaches the level (value below
// it); infinity when it never does.
double firstReach(double value, double slope, double curvature, double level) {
    const double gap = level - value;
    const double disc = slope * slope + 2.0 * curvature * gap;
    if (disc < 0.0) return INFINITY;  // a downward parabola peaking below the level
    const double root = std::sqrt(disc);
    // Written to avoid cancellation when slope > 0.
    if (slope > 0.0) return 2.0 * gap / (slope + root);
    return curvature > 0.0 ? (root - slope) / curvature : INFINITY;
}

}  // namespace

TWINRENDER_VECTOR_CLONES
Crossing findFirstCrossing(const RayField& field, double ta, double tb,
                           const CrossingSettings& settings, double hint) {
    Crossing out;
    const double level = settings.level, tolerance = settings.tolerance;
    double a = ta;
    if (hint > ta && hint < tb) {
        ++out.evaluations;
        // Pieces shorter toward the hint, where phi comes closest to the level; the search
        // starts after the last of the pieces that begin it proven below the level.
        const double points[] = {ta, std::max(ta, hint - HINT_PIECES[0] * settings.maxStep),
                                 std::max(ta, hint - HINT_PIECES[1] * settings.maxStep), hint};
        double bounds[BOUND_PIECES];
        piecewiseBound(field, points, bounds);
        for (int k = 0; k < BOUND_PIECES && bounds[k] < level; ++k) a = points[k + 1];
    }
    double previous = a;
    // The curvature bounds of the last full sample hold up to boundsEnd: while the window left
    // reaches past the last step (converging on a root, the steps shrink), phi and phi' alone
    // suffice.
    double boundsEnd = -INFINITY, upper = 0.0, lower = 0.0, lastStep = INFINITY;
    for (int it = 0; it < settings.maxIterations; ++it) {
        double window = boundsEnd - a;
        FieldSample f;
        if (window >= lastStep) {
            f = sampleValue(field, a);
            f.curvature = upper;
            f.curvatureLow = lower;
            f.ahead = INFINITY;
        } else {
            window = std::min(settings.maxStep, tb - a);
            f = sampleField(field, a, window, tb - a);
            boundsEnd = a + window;
            upper = f.curvature;
            lower = f.curvatureLow;
        }
        ++out.evaluations;
        if (f.value >= level) {
            // At the start: the ray begins inside. Later the step can only land exactly on the
            // root (the bound touches the level there): a hit.
            out.status = it == 0 && a == ta ? Crossing::Status::Inside : Crossing::Status::Hit;
            out.t = a;
            out.tBelow = it == 0 ? a : previous;
            return out;
        }
        previous = a;
        if (f.ahead < level) {
            // Nothing ahead can reach the level.
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
        // phi < level on [a, a + step); phi(a + sure) >= level.
        const double step = firstReach(f.value, f.slope, f.curvature, level);
        const bool nearRoot = (f.curvature - f.curvatureLow) * step * step <=
                              2.0 * BRACKET_ESTIMATE_SLACK * tolerance * f.slope;
        const double sure =
            nearRoot ? firstReach(f.value, f.slope, f.curvatureLow, level) : INFINITY;
        // Going away from the surface (a shadow ray leaving its start): phi stays below the
        // level up to the next point; the bound of what lies beyond is cheaper than a sample.
        const double next = a + std::min(step, window);
        if (f.slope <= 0.0 && next < tb && intervalBound(field, next, tb) < level) {
            ++out.evaluations;
            out.status = Crossing::Status::Miss;
            out.tBelow = tb;
            return out;
        }
        if (sure <= window && sure - step <= tolerance) {
            // The first root is bracketed within the tolerance: take the Newton estimate
            // inside the bracket.
            out.status = Crossing::Status::Hit;
            out.t = a + std::clamp((level - f.value) / f.slope, step, sure);
            out.tBelow = a + std::max(0.0, step - BELOW_MARGIN * tolerance);
            return out;
        }
        if (step < tolerance) {
            // The bound says the root may be closer than the tolerance: confirm it.
            const double b = a + tolerance;
            const FieldSample fb = sampleValue(field, b);
            ++out.evaluations;
            if (fb.value >= level) {
                const double frac = (level - f.value) / (fb.value - f.value);
                out.status = Crossing::Status::Hit;
                out.tBelow = a;
                out.t = a + tolerance * std::clamp(frac, 0.0, 1.0);
                return out;
            }
            a = b;  // grazing past a tangency; the next step starts below the level
            lastStep = tolerance;
        } else {
            lastStep = std::min(step, window);
            a += lastStep;
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
