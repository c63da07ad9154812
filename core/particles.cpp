#include "core/particles.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <limits>
#include <map>
#include <stdexcept>

#include "core/body_motion.h"
#include "core/derived_attributes.h"
#include "core/error.h"
#include "core/particle_file.h"
#include "core/particle_generators.h"
#include "core/scene.h"
#include "core/sph_kernel.h"

namespace twinrender::core {

void ParticleSet::resize(std::size_t n) {
    position.resize(n);
    h.resize(n);
    volume.resize(n);
    body.resize(n);
    material.resize(n);
    uv.resize(n);
    dudx.resize(n);
    dvdx.resize(n);
    normal.resize(n);
    temperature.resize(n);
    glow.resize(n);
}

namespace {

std::string whereOf(const BodyDesc& desc) {
    return desc.where.empty() ? "scene" : desc.where;
}

glm::dmat3 frameOf(const BodyDesc& desc) {
    try {
        return bodyFrame(desc.normal);
    } catch (const std::invalid_argument& e) {
        throw InputError(
            fmt::format("{}: body '{}': normal: {}", whereOf(desc), desc.name, e.what()));
    }
}

// Appends a generated body (ball, shell, ring).
void appendGenerated(const BodyDesc& desc, const Scene& scene, ParticleSet& set,
                     std::vector<BodyInfo>& bodies, std::vector<bool>& keepUv) {
    GeneratedBody gen = generateBody(desc);
    const std::size_t begin = set.size();
    const std::size_t n = gen.size();
    set.resize(begin + n);
    std::copy(gen.position.begin(), gen.position.end(), set.position.begin() + begin);
    const auto bodyIndex = static_cast<std::uint32_t>(bodies.size());
    std::fill_n(set.h.begin() + begin, n, static_cast<float>(gen.h));
    std::fill_n(set.volume.begin() + begin, n, static_cast<float>(gen.volume));
    std::fill_n(set.body.begin() + begin, n, bodyIndex);
    std::fill_n(set.material.begin() + begin, n, desc.materialIndex);
    std::fill_n(set.temperature.begin() + begin, n, static_cast<float>(desc.temperature));

    BodyInfo info;
    info.name = desc.name;
    info.material = desc.materialIndex;
    info.center = desc.center;
    info.frame = frameOf(desc);
    info.begin = begin;
    info.end = begin + n;
    info.meanH = gen.h;
    applyMotion(desc, scene.time, scene.frame, std::span<glm::vec3>(set.position).subspan(begin, n),
                gen.h, info);
    bodies.push_back(std::move(info));
    keepUv.push_back(false);
}

// Particles are float32 in scene units (ParticleSet): a file's position or h (valid as the
// reader's doubles) that, scaled, has no float form, or an h below the smallest normal float
// (whose kernel terms 1 / h^4 overflow), is rejected naming the file and the particle.
void checkFitsFloat(const BodyDesc& desc, std::size_t i, const glm::dvec3& p, double h) {
    constexpr double MOST = std::numeric_limits<float>::max();
    constexpr double LEAST_H = std::numeric_limits<float>::min();
    const char* scaled = desc.scale == 1.0 ? "" : " after the body's scale";
    if (!(std::abs(p.x) <= MOST && std::abs(p.y) <= MOST && std::abs(p.z) <= MOST))
        throw InputError(fmt::format(
            "{}: particle {}: position ({}, {}, {}){} is beyond the float range (|x| <= {:g}); "
            "fix the file, or lower the body's scale in {}",
            desc.path.string(), i, p.x, p.y, p.z, scaled, MOST, whereOf(desc)));
    if (!(h >= LEAST_H && h <= MOST))
        throw InputError(fmt::format(
            "{}: particle {}: smoothing length h = {}{} is outside the float range [{:g}, {:g}]; "
            "fix the file, or change the body's scale in {}",
            desc.path.string(), i, h, scaled, LEAST_H, MOST, whereOf(desc)));
}

// Appends a body read from a particle file. A file with a body column holding several values
// (OpenSPH's flag: impactor and target) becomes one BodyInfo per value, in ascending order,
// named "<name>.<value>", each with its own centre; particles keep their file order within
// each. Particle ranges of BodyInfo must be contiguous, hence the stable partition by value.
void appendFile(const BodyDesc& desc, ParticleSet& set, std::vector<BodyInfo>& bodies,
                std::vector<bool>& keepUv) {
    const ParticleFileData file = readParticleFile(desc.path);
    const std::size_t n = file.size();
    if (n == 0)
        throw InputError(fmt::format("{}: body '{}': {} holds no particles", whereOf(desc),
                                     desc.name, desc.path.string()));
    if (!(std::isfinite(desc.scale) && desc.scale > 0.0))
        throw InputError(fmt::format("{}: body '{}': scale must be a positive number (got {})",
                                     whereOf(desc), desc.name, desc.scale));
    const glm::dmat3 frame = frameOf(desc);
    const bool hasMassDensity = file.mass.size() == n && file.density.size() == n;
    const bool hasUv = file.uv.size() == n;
    const bool hasTemperature = file.temperature.size() == n;

    // Group the particle indices by the file's body value (a single group without a column).
    std::map<std::int64_t, std::vector<std::size_t>> groups;
    if (file.body.size() == n) {
        for (std::size_t i = 0; i < n; ++i) groups[file.body[i]].push_back(i);
    } else {
        auto& all = groups[0];
        all.resize(n);
        for (std::size_t i = 0; i < n; ++i) all[i] = i;
    }

    std::size_t next = set.size();
    set.resize(next + n);
    for (const auto& [value, indices] : groups) {
        const std::size_t begin = next;
        const auto bodyIndex = static_cast<std::uint32_t>(bodies.size());
        // uv centre: the centre of mass of the group when the file has masses, else the
        // mean position (both after scale and translation).
        glm::dvec3 weighted(0.0);
        double weight = 0.0;
        double sumH = 0.0;
        for (std::size_t i : indices) {
            const glm::dvec3 p = desc.center + desc.scale * file.position[i];
            const double h = desc.scale * file.h[i];
            const double m = file.mass.size() == n ? file.mass[i] : 1.0;
            weighted += m * p;
            weight += m;
            sumH += h;
            double v = maxParticleVolume(h);
            if (hasMassDensity && file.density[i] > 0.0 && file.mass[i] > 0.0)
                // m / rho in file units^3, scaled like the positions.
                v = std::min(file.mass[i] / file.density[i] * desc.scale * desc.scale * desc.scale,
                             v);
            checkFitsFloat(desc, i, p, h);
            set.position[next] = glm::vec3(p);
            set.h[next] = static_cast<float>(h);
            set.volume[next] = static_cast<float>(v);
            set.body[next] = bodyIndex;
            set.material[next] = desc.materialIndex;
            set.temperature[next] =
                static_cast<float>(hasTemperature ? file.temperature[i] : desc.temperature);
            if (hasUv) set.uv[next] = glm::vec2(file.uv[i]);
            ++next;
        }
        BodyInfo info;
        info.name = groups.size() > 1 ? fmt::format("{}.{}", desc.name, value) : desc.name;
        info.material = desc.materialIndex;
        // Zero or negative total mass (no usable masses): fall back to the mean position.
        if (!(weight > 0.0)) {
            weighted = glm::dvec3(0.0);
            for (std::size_t i : indices) weighted += desc.center + desc.scale * file.position[i];
            weight = static_cast<double>(indices.size());
        }
        info.center = weighted / weight;
        info.frame = frame;
        info.begin = begin;
        info.end = next;
        info.meanH = sumH / static_cast<double>(indices.size());
        bodies.push_back(std::move(info));
        keepUv.push_back(hasUv);
    }
}

}  // namespace

SceneParticles buildParticles(const Scene& scene) {
    SceneParticles out;
    std::vector<bool> keepUv;
    for (const BodyDesc& desc : scene.bodies) {
        if (desc.shape == Shape::File)
            appendFile(desc, out.particles, out.bodies, keepUv);
        else
            appendGenerated(desc, scene, out.particles, out.bodies, keepUv);
    }
    ParticleSet& set = out.particles;
    if (set.size() > std::numeric_limits<std::uint32_t>::max())
        throw InputError(fmt::format("scene '{}': {} particles, more than the {} supported",
                                     scene.name, set.size(),
                                     std::numeric_limits<std::uint32_t>::max()));

    for (std::size_t b = 0; b < out.bodies.size(); ++b)
        deriveUv(set, out.bodies[b], b < keepUv.size() && keepUv[b]);
    deriveGlow(set);
    out.hasNormals = false;

    if (set.size() > 0) {
        glm::dvec3 lo(INFINITY), hi(-INFINITY);
        for (std::size_t i = 0; i < set.size(); ++i) {
            const glm::dvec3 p(set.position[i]);
            const double r = M4_SUPPORT * set.h[i];
            lo = glm::min(lo, p - r);
            hi = glm::max(hi, p + r);
        }
        out.boundsMin = lo;
        out.boundsMax = hi;
    }
    return out;
}

void deriveNormals(SceneParticles& particles) {
    deriveNormals(particles.particles, particles.bodies);
    particles.hasNormals = true;
}

}  // namespace twinrender::core
