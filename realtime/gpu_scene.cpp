#include "realtime/gpu_scene.h"

#include <fmt/format.h>

#include <memory>
#include <numbers>
#include <stdexcept>

#include "core/sph_kernel.h"

namespace twinrender::realtime {

namespace {
// Float represents every integer below 2^24 exactly.
constexpr std::uint32_t MAX_EXACT_INDEX = 1u << 24;
}  // namespace

std::vector<GpuParticle> packParticles(const core::ParticleSet& ps, const glm::dvec3& camera,
                                       std::span<const float> radii,
                                       std::span<const std::uint32_t> indices,
                                       std::span<const FieldNormal> fieldNormals) {
    const std::size_t n = indices.empty() ? ps.size() : indices.size();
    if (!fieldNormals.empty() && fieldNormals.size() != n)
        throw std::invalid_argument(fmt::format("packParticles: {} field normals for {} particles",
                                                fieldNormals.size(), n));
    std::vector<GpuParticle> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = indices.empty() ? k : indices[k];
        if (ps.body[i] >= MAX_EXACT_INDEX || ps.material[i] >= MAX_EXACT_INDEX)
            throw std::invalid_argument(
                fmt::format("particle {}: body {} or material {} is not exact as a float id", i,
                            ps.body[i], ps.material[i]));
        const glm::dvec3 relative = glm::dvec3(ps.position[i]) - camera;
        GpuParticle& g = out[k];
        g.positionRadius = glm::vec4(glm::vec3(relative), radii[i]);
        g.normalU = glm::vec4(ps.normal[i], ps.uv[i].x);
        g.dudxV = glm::vec4(ps.dudx[i], ps.uv[i].y);
        g.dvdxBody = glm::vec4(ps.dvdx[i], static_cast<float>(ps.body[i]));
        g.glowMaterial = glm::vec4(ps.glow[i], static_cast<float>(ps.material[i]));
        if (!fieldNormals.empty()) {
            const FieldNormal& f = fieldNormals[k];
            g.normalU = glm::vec4(f.outward, ps.uv[i].x);
            g.hessianDiagonal = glm::vec4(f.diagonal, 0.0f);
            g.hessianOffDiagonal = glm::vec4(f.offDiagonal, 0.0f);
        }
    }
    return out;
}

std::vector<GpuParticle> packBodySpheres(std::span<const core::BodySphere> spheres,
                                         std::span<const core::BodyInfo> bodies,
                                         const glm::dvec3& camera) {
    std::vector<GpuParticle> out(spheres.size());
    for (std::size_t k = 0; k < spheres.size(); ++k) {
        const core::BodySphere& s = spheres[k];
        const core::BodyInfo& body = bodies[s.body];
        if (s.body >= MAX_EXACT_INDEX || body.material >= MAX_EXACT_INDEX)
            throw std::invalid_argument(
                fmt::format("body {}: its index or material {} is not exact as a float id", s.body,
                            body.material));
        GpuParticle& g = out[k];
        g.positionRadius = glm::vec4(glm::vec3(s.centre - camera), static_cast<float>(s.radius));
        g.normalU = glm::vec4(glm::vec3(body.frame[0]), 0.0f);
        g.dudxV = glm::vec4(glm::vec3(body.frame[1]), 0.0f);
        g.dvdxBody = glm::vec4(glm::vec3(body.frame[2]), static_cast<float>(s.body));
        g.glowMaterial = glm::vec4(s.glow, static_cast<float>(body.material));
        g.hessianDiagonal = glm::vec4(glm::vec3(body.center - s.centre), 0.0f);
    }
    return out;
}

std::vector<GpuEllipsoid> packEllipsoids(std::span<const Ellipsoid> ellipsoids,
                                         std::span<const std::uint32_t> indices) {
    const std::size_t n = indices.empty() ? ellipsoids.size() : indices.size();
    std::vector<GpuEllipsoid> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        const Ellipsoid& e = ellipsoids[indices.empty() ? k : indices[k]];
        for (int a = 0; a < 3; ++a) out[k].axisShift[a] = glm::vec4(e.axes[a], e.shift[a]);
    }
    return out;
}

std::vector<GpuKernel> packKernels(const core::ParticleSet& ps, const glm::dvec3& camera,
                                   std::span<const std::uint32_t> indices) {
    const std::size_t n = indices.empty() ? ps.size() : indices.size();
    std::vector<GpuKernel> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = indices.empty() ? k : indices[k];
        const double h = ps.h[i];
        out[k].positionSupport = glm::vec4(glm::vec3(glm::dvec3(ps.position[i]) - camera),
                                           static_cast<float>(core::M4_SUPPORT * h));
        out[k].coefficients =
            glm::vec4(static_cast<float>(ps.volume[i] / (std::numbers::pi * h * h * h * h)),
                      static_cast<float>(1.0 / h), 0.0f, 0.0f);
    }
    return out;
}

GpuMaterials packMaterials(const std::vector<core::Material>& materials) {
    GpuMaterials out;
    std::vector<std::pair<const core::Image*, int>> stored;  // image, first float
    static const core::Image black(1, 1, {"R", "G", "B"});
    std::vector<std::unique_ptr<core::Image>> uniforms;  // 1x1 stand-ins, alive while packing
    auto add = [&](const core::Texture& t) {
        // A texture never loaded (no pixels) reads as black; one of a single colour (a baked
        // "procedural:none", say) is stored as 1x1: bilinear sampling gives the same value
        // with one fetch instead of four.
        const core::Image* source = t.image().pixelCount() == 0 ? &black : &t.image();
        if (source->pixelCount() > 1 && source->channelCount() == 3) {
            const auto px = source->pixels();
            bool uniform = true;
            for (std::size_t k = 3; k < px.size() && uniform; ++k) uniform = px[k] == px[k % 3];
            if (uniform) {
                auto one =
                    std::make_unique<core::Image>(1, 1, std::vector<std::string>{"R", "G", "B"});
                for (int c = 0; c < 3; ++c) one->at(0, 0, c) = px[c];
                source = one.get();
                uniforms.push_back(std::move(one));
            }
        }
        const core::Image& image = *source;
        for (const auto& [other, offset] : stored)
            if (*other == image) return glm::ivec4(offset / 3, image.width(), image.height(), 0);
        if (image.channelCount() != 3)
            throw std::invalid_argument("material textures must have 3 channels (R, G, B)");
        const auto offset = out.texels.size();
        if (offset + image.pixels().size() > static_cast<std::size_t>(INT32_MAX))
            throw std::length_error("material textures exceed 2^31 floats");
        out.texels.insert(out.texels.end(), image.pixels().begin(), image.pixels().end());
        stored.emplace_back(&image, static_cast<int>(offset));
        return glm::ivec4(static_cast<int>(offset / 3), image.width(), image.height(), 0);
    };
    for (const auto& m : materials) {
        GpuMaterial g;
        g.diffuse = add(m.diffuse);
        g.specular = add(m.specular);
        g.emission = add(m.emission);
        g.cityLights = add(m.cityLights);
        g.params = glm::vec4(m.shininess, 0.0f, 0.0f, 0.0f);
        out.records.push_back(g);
    }
    return out;
}

}  // namespace twinrender::realtime
