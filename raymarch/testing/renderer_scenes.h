// Test scenes of the reference renderer (raymarch/renderer_test.cpp,
// raymarch/renderer_rounds_test.cpp): particles given one body at a time, rendered on an arena
// of a given thread count, and one sphere over a lattice floor whose shadow, occlusion and
// light have closed forms.
#pragma once

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "core/sph_kernel.h"
#include "raymarch/renderer.h"
#include "raymarch/testing/ray_field_testing.h"

namespace twinrender::raymarch::testing {

struct TestScene {
    core::Scene scene;
    core::SceneParticles particles;
    std::vector<core::Material> materials;

    TestScene() {
        scene.name = "test";
        scene.camera.width = 64;
        scene.camera.height = 64;
        scene.light.direction = {0.0, 0.0, -1.0};
        core::MaterialDesc m;
        m.name = "white";
        m.diffuse.value = glm::dvec3(0.8);
        scene.materials.push_back(m);
        materials = core::loadMaterials(scene);
    }

    // Appends particles as one body (uv, normals and glow are not needed by these tests).
    void addBody(const std::vector<glm::vec3>& positions, float h, float volume) {
        auto& ps = particles.particles;
        const std::size_t begin = ps.size();
        ps.resize(begin + positions.size());
        core::BodyInfo body;
        body.name = "body" + std::to_string(particles.bodies.size());
        body.begin = begin;
        body.end = ps.size();
        body.meanH = h;
        for (std::size_t i = 0; i < positions.size(); ++i) {
            ps.position[begin + i] = positions[i];
            ps.h[begin + i] = h;
            ps.volume[begin + i] = volume;
            ps.body[begin + i] = static_cast<std::uint32_t>(particles.bodies.size());
            ps.normal[begin + i] = {0, 0, 1};
            particles.boundsMin = glm::min(particles.boundsMin, glm::dvec3(positions[i]) - 2.0 * h);
            particles.boundsMax = glm::max(particles.boundsMax, glm::dvec3(positions[i]) + 2.0 * h);
        }
        particles.bodies.push_back(body);
    }
};

inline core::Frame render(const TestScene& s, const Settings& settings, int threads = 2) {
    EmbreeDevice device;
    core::Frame frame;
    tbb::task_arena arena(threads);
    arena.execute([&] {
        Renderer renderer(device, settings);
        frame = renderer.render({s.scene, s.particles, s.materials});
    });
    return frame;
}

// One particle (an exact sphere) above a lattice floor, lit at 37 degrees from the vertical,
// seen from above.
struct SphereOverFloor {
    TestScene s;
    Settings settings;
    double radius = 0.0;  // the sphere's
    const glm::dvec3 toLight{-0.6, 0.0, 0.8}, centre{0.0, 0.0, 1.0};

    SphereOverFloor() {
        const float spacing = 0.1f, h = 1.3f * spacing;
        const float v = std::min(spacing * spacing * spacing, float(core::maxParticleVolume(h)));
        std::vector<glm::vec3> floor;
        for (int i = -25; i <= 25; ++i)
            for (int j = -25; j <= 25; ++j)
                for (int k = 0; k < 3; ++k)
                    floor.emplace_back(i * spacing, j * spacing, -k * spacing);
        s.addBody(floor, h, v);
        // The ball's support (2 h = 0.8) stays clear of the floor's, so its surface is an exact
        // sphere: its volume is chosen so that the field peaks at twice the level.
        const float hBall = 0.4f;
        const float vBall = float(2.0 * settings.surfaceLevel / core::m4Kernel(0.0, double(hBall)));
        s.addBody({glm::vec3(centre)}, hBall, vBall);
        radius = singleParticleRadius(vBall, hBall, settings.surfaceLevel);
        s.scene.light.direction = -toLight;
        s.scene.camera.position = {0.3, -0.01, 4.0};
        s.scene.camera.target = {0.3, 0.0, 0.0};
        s.scene.camera.up = {0.0, 1.0, 0.0};
        s.scene.camera.fovYDeg = 25.0;
        s.scene.camera.width = s.scene.camera.height = 64;
    }

    // Calls visit(x, y, p, angle, pixel) for each floor pixel: its point p, the angle between
    // toLight and the direction from p to the sphere's centre minus the sphere's angular radius
    // seen from p (radians; negative: the light's centre is behind the sphere), and the angle a
    // pixel's footprint spans there.
    template <typename Visit>
    void forEachFloorPixel(const core::Image& img, Visit&& visit) const {
        const core::Camera camera(s.scene.camera);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                if (img.at(x, y, img.channelIndex("id")) != 0.0f) continue;  // the floor only
                const auto ray = camera.ray(x + 0.5, y + 0.5);
                const double t =
                    img.at(x, y, img.channelIndex("Z")) / glm::dot(ray.direction, camera.forward());
                const glm::dvec3 p = ray.origin + t * ray.direction;
                const glm::dvec3 toCentre = centre - p;
                const double d = glm::length(toCentre);
                const double between =
                    std::acos(std::clamp(glm::dot(toCentre / d, toLight), -1.0, 1.0));
                const double angle = between - std::asin(radius / d);
                // A pixel's footprint on the floor, stretched by the light's slant.
                const double pixel = 2.0 * 2.0 * t * camera.tanHalfFovY() / 64.0 / d;
                visit(x, y, p, angle, pixel);
            }
    }

    // Gives the sphere a material of uniform emitted radiance and no diffuse reflection.
    void makeTheSphereGlow(const glm::dvec3& radiance) {
        core::MaterialDesc glowing;
        glowing.name = "glowing";
        glowing.diffuse.value = glm::dvec3(0.0);
        glowing.emission.value = radiance;
        s.scene.materials.push_back(glowing);
        s.materials = core::loadMaterials(s.scene);
        const auto material = static_cast<std::uint32_t>(s.scene.materials.size() - 1);
        s.particles.bodies[1].material = material;
        for (std::size_t i = s.particles.bodies[1].begin; i < s.particles.bodies[1].end; ++i)
            s.particles.particles.material[i] = material;
    }

    // The solid angle of the cone the reference samples toward the glowing sphere from
    // distance d: that of the sphere around its one particle's support (2 h = 0.8).
    static double supportSolidAngle(double d) {
        const double support = 0.8;
        return 2.0 * std::numbers::pi * (1.0 - std::sqrt(1.0 - (support / d) * (support / d)));
    }

    // Calls visit(x, y, p, d, cosBeta) for each floor pixel from which the sphere lies wholly
    // above the horizon of the normal the image holds (by a margin of 0.02 rad): its point p,
    // its distance d from the sphere's centre and the cosine of the angle beta between the
    // normal and the centre. The closed forms of the sphere's occlusion and light hold there.
    template <typename Visit>
    void forEachFloorPixelUnderTheSphere(const core::Image& img, Visit&& visit) const {
        const int nx = img.channelIndex("N.X");
        forEachFloorPixel(img, [&](int x, int y, const glm::dvec3& p, double, double) {
            const glm::dvec3 n(img.at(x, y, nx), img.at(x, y, nx + 1), img.at(x, y, nx + 2));
            const glm::dvec3 toCentre = centre - p;
            const double d = glm::length(toCentre);
            const double cosBeta = glm::dot(n, toCentre) / d;
            if (std::acos(std::clamp(cosBeta, -1.0, 1.0)) + std::asin(radius / d) >
                0.5 * std::numbers::pi - 0.02)
                return;
            visit(x, y, p, d, cosBeta);
        });
    }
};

}  // namespace twinrender::raymarch::testing
