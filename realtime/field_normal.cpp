#include "realtime/field_normal.h"

#include <algorithm>
#include <glm/geometric.hpp>

#include "core/derived_attributes.h"

namespace twinrender::realtime {

std::vector<FieldNormal> fieldNormals(const core::ParticleSet& ps, std::span<const float> radii,
                                      std::span<const std::uint32_t> indices) {
    const std::size_t n = indices.empty() ? ps.size() : indices.size();
    auto particle = [&](std::size_t k) { return indices.empty() ? k : indices[k]; };
    std::vector<glm::dvec3> tops(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = particle(k);
        tops[k] = glm::dvec3(ps.position[i]) + double(radii[i]) * glm::dvec3(ps.normal[i]);
    }
    const std::vector<core::FieldDerivatives> d = core::colourFieldDerivatives(ps, tops);
    std::vector<FieldNormal> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = particle(k);
        const double length = glm::length(d[k].gradient);
        FieldNormal& f = out[k];
        if (!(length > 0.0)) {
            f.outward = ps.normal[i];
            continue;
        }
        // -grad c(x) / |g_top| = -(g_top + H (x - x_top)) / |g_top|, rewritten about the centre:
        // x - x_top = (x - x_i) - r n_i.
        const glm::dmat3 h = -d[k].hessian / length;
        const glm::dvec3 offsetTop = double(radii[i]) * glm::dvec3(ps.normal[i]);
        f.outward = glm::vec3(-d[k].gradient / length - h * offsetTop);
        f.diagonal = glm::vec3(h[0][0], h[1][1], h[2][2]);
        f.offDiagonal = glm::vec3(h[0][1], h[0][2], h[1][2]);
    }
    return out;
}

const std::vector<FieldNormal>& FieldNormalCache::normals(const core::ParticleSet& ps,
                                                          std::span<const float> radii,
                                                          std::span<const std::uint32_t> indices) {
    return mCache.get(
        ps, [&] { return fieldNormals(ps, radii, indices); }, radii, indices);
}

}  // namespace twinrender::realtime
