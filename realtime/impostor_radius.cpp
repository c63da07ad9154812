#include "realtime/impostor_radius.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <glm/geometric.hpp>

#include "core/colour_field.h"

namespace twinrender::realtime {

namespace {

// Samples along the normal before the bisection: a crossing between two samples is found
// unless the field dips below the level and back within one step (radius_scale * h / 8).
constexpr int SCAN_STEPS = 8;
// Bisection steps: the radius to (radius_scale * h / 8) / 2^10, about 1e-4 h.
constexpr int BISECTION_STEPS = 10;

}  // namespace

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
    const double level = settings.surfaceLevel;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ps.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              const glm::dvec3 centre(ps.position[i]);
                              const glm::dvec3 normal = glm::normalize(glm::dvec3(ps.normal[i]));
                              const double maxRadius = settings.radiusScale * ps.h[i];
                              if (!(field.value(centre) > level)) {
                                  radii[i] = 0.0f;
                                  continue;
                              }
                              double inside = 0.0, outside = -1.0;
                              for (int k = 1; k <= SCAN_STEPS; ++k) {
                                  const double t = maxRadius * k / SCAN_STEPS;
                                  if (field.value(centre + t * normal) > level) {
                                      inside = t;
                                  } else {
                                      outside = t;
                                      break;
                                  }
                              }
                              if (outside < 0.0) {
                                  radii[i] = static_cast<float>(maxRadius);
                                  continue;
                              }
                              for (int k = 0; k < BISECTION_STEPS; ++k) {
                                  const double t = 0.5 * (inside + outside);
                                  (field.value(centre + t * normal) > level ? inside : outside) = t;
                              }
                              radii[i] = static_cast<float>(std::min(
                                  maxRadius, settings.crossingScale * 0.5 * (inside + outside)));
                          }
                      });
    return radii;
}

}  // namespace twinrender::realtime
