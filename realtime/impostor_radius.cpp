#include "realtime/impostor_radius.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <glm/geometric.hpp>

#include "core/colour_field.h"
#include "core/sph_kernel.h"

namespace twinrender::realtime {

// Samples along the normal before the bisection: a crossing between two samples is found
// unless the field dips below the level and back within one step (maxRadius / 8), or, for a
// particle whose field is above the level at the cap and halfway there, within half the cap.
constexpr int SCAN_STEPS = 8;
// Bisection steps: the crossing to (maxRadius / 8) / 2^10, about 1e-4 h.
constexpr int BISECTION_STEPS = 10;

double fieldCrossing(const core::ColourField& field, const glm::dvec3& centre,
                     const glm::dvec3& normal, double maxRadius, double level) {
    auto above = [&](double t) { return field.value(centre + t * normal) > level; };
    if (!above(0.0)) return 0.0;
    // Particles inside a body (most of them) are settled by two samples.
    if (above(maxRadius) && above(0.5 * maxRadius)) return maxRadius;
    double inside = 0.0, outside = -1.0;
    for (int k = 1; k <= SCAN_STEPS && outside < 0.0; ++k) {
        const double t = maxRadius * k / SCAN_STEPS;
        (above(t) ? inside : outside) = t;
    }
    if (outside < 0.0) return maxRadius;
    for (int k = 0; k < BISECTION_STEPS; ++k) {
        const double t = 0.5 * (inside + outside);
        (above(t) ? inside : outside) = t;
    }
    return 0.5 * (inside + outside);
}

std::vector<float> fixedRadii(const core::ParticleSet& ps, double radiusScale) {
    std::vector<float> radii(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i)
        radii[i] = static_cast<float>(radiusScale * ps.h[i]);
    return radii;
}

std::vector<float> impostorRadii(const core::ParticleSet& ps, const ParticleSettings& settings) {
    if (settings.radius == RadiusModel::Fixed) return fixedRadii(ps, settings.radiusScale);
    std::vector<float> radii(ps.size());
    const core::ColourField field(ps);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, ps.size(), 256),
        [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const double maxRadius = settings.radiusScale * ps.h[i];
                const glm::dvec3 centre(ps.position[i]);
                // A particle alone in its support has a spherical droplet: the crossing is its
                // radius exactly. crossing_scale is for the level set bulging between
                // neighbours. One deep inside a body (interior_level) reaches the cap.
                const double own = ps.volume[i] * core::m4Kernel(0.0, double(ps.h[i]));
                const double atCentre = field.value(centre);
                const bool alone = atCentre <= own * (1.0 + 1e-4);
                const double crossing =
                    !alone && atCentre > settings.surfaceLevel && atCentre >= settings.interiorLevel
                        ? maxRadius
                        : fieldCrossing(field, centre, glm::normalize(glm::dvec3(ps.normal[i])),
                                        maxRadius, settings.surfaceLevel);
                radii[i] = static_cast<float>(
                    std::min(maxRadius, (alone ? 1.0 : settings.crossingScale) * crossing));
            }
        });
    return radii;
}

const std::vector<float>& ImpostorRadiusCache::radii(const core::ParticleSet& ps,
                                                     const ParticleSettings& settings) {
    const RadiusSettings key{settings.radius, settings.radiusScale, settings.surfaceLevel,
                             settings.crossingScale, settings.interiorLevel};
    return mCache.get(
        ps, [&] { return impostorRadii(ps, settings); }, key);
}

}  // namespace twinrender::realtime
