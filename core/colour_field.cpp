#include "core/colour_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/sph_kernel.h"

namespace twinrender::core {

ColourField::ColourField(const ParticleSet& particles) : mParticles(particles), mGrid(particles) {}

double ColourField::value(const glm::dvec3& p) const {
    double sum = 0.0;
    mGrid.visitSupport(p,
                       [&](const ParticleGrid::Level& g, std::uint32_t begin, std::uint32_t end) {
                           for (std::uint32_t j = begin; j < end; ++j) {
                               const glm::dvec3 delta = p - glm::dvec3(g.px[j], g.py[j], g.pz[j]);
                               const double q = glm::length(delta) * g.invH[j];
                               if (q >= M4_SUPPORT) continue;
                               // coef = v / (pi h^4): W = coef h w(q).
                               sum += g.coef[j] / g.invH[j] * m4Shape(q);
                           }
                       });
    return sum;
}

FieldDerivatives ColourField::derivatives(const glm::dvec3& p) const {
    FieldDerivatives d;
    mGrid.visitSupport(
        p, [&](const ParticleGrid::Level& g, std::uint32_t begin, std::uint32_t end) {
            for (std::uint32_t j = begin; j < end; ++j) {
                const glm::dvec3 delta = p - glm::dvec3(g.px[j], g.py[j], g.pz[j]);
                const double r = glm::length(delta);
                const double invH = g.invH[j];
                const double q = r * invH;
                if (q >= M4_SUPPORT || r == 0.0) continue;
                // dW/dr = coef w'(q), d2W/dr2 = coef w''(q) / h (coef = v / (pi h^4)).
                const double dWdr = g.coef[j] * m4ShapeDerivative(q);
                const double d2Wdr2 = g.coef[j] * invH * m4ShapeSecondDerivative(q);
                const glm::dvec3 u = delta / r;
                d.gradient += dWdr * u;
                // Hessian of W(|x - x_j|): W'' u u^T + (W' / r) (I - u u^T).
                d.hessian += (d2Wdr2 - dWdr / r) * glm::outerProduct(u, u) + glm::dmat3(dWdr / r);
            }
        });
    return d;
}

std::vector<FieldDerivatives> colourFieldDerivatives(const ParticleSet& set,
                                                     std::span<const glm::dvec3> points) {
    std::vector<FieldDerivatives> out(points.size());
    if (set.size() == 0 || points.empty()) return out;
    const ColourField field(set);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t k = range.begin(); k != range.end(); ++k)
                              out[k] = field.derivatives(points[k]);
                      });
    return out;
}

}  // namespace twinrender::core
