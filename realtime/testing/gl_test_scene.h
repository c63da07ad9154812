// Scenes built in code for the real-time renderer's GL tests (small images, few particles):
// uv, normals and bodies are exactly what each test needs.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <functional>
#include <glm/geometric.hpp>
#include <limits>

#include "core/camera.h"
#include "realtime/gl/context.h"
#include "realtime/renderer.h"

namespace twinrender::realtime::testing {

constexpr int WIDTH = 160, HEIGHT = 90;

inline core::Texture constantTexture(glm::vec3 c) {
    core::Image image(1, 1, {"R", "G", "B"});
    for (int i = 0; i < 3; ++i) image.at(0, 0, i) = c[i];
    return core::Texture(std::move(image));
}

struct TestScene {
    core::Scene scene;
    core::SceneParticles particles;
    std::vector<core::Material> materials;

    TestScene() {
        scene.name = "test";
        scene.file = "test.toml";
        scene.camera.position = {0.0, 0.0, 10.0};
        scene.camera.target = {0.0, 0.0, 0.0};
        scene.camera.up = {0.0, 1.0, 0.0};
        scene.camera.fovYDeg = 30.0;
        scene.camera.near = 0.1;
        scene.camera.far = 100.0;
        scene.camera.width = WIDTH;
        scene.camera.height = HEIGHT;
        scene.light.direction = glm::normalize(glm::dvec3(0.0, 0.0, -1.0));
        scene.light.intensity = 2.0;
        scene.light.ambient = 0.05;
        core::Material grey;
        grey.name = "grey";
        grey.diffuse = constantTexture(glm::vec3(0.5f));
        grey.specular = constantTexture(glm::vec3(0.0f));
        grey.emission = constantTexture(glm::vec3(0.0f));
        grey.cityLights = constantTexture(glm::vec3(0.0f));
        materials.push_back(grey);
    }

    // One particle; returns its index.
    std::size_t add(std::uint32_t body, glm::vec3 position, float h, glm::vec2 uv = {0.5f, 0.5f},
                    glm::vec3 normal = {0.0f, 0.0f, 1.0f}) {
        core::ParticleSet& ps = particles.particles;
        const std::size_t i = ps.size();
        ps.resize(i + 1);
        ps.position[i] = position;
        ps.h[i] = h;
        ps.volume[i] = h * h * h / 2.197f;
        ps.body[i] = body;
        ps.material[i] = 0;
        ps.uv[i] = uv;
        ps.dudx[i] = ps.dvdx[i] = glm::vec3(0.0f);
        ps.normal[i] = normal;
        ps.temperature[i] = 0.0f;
        ps.glow[i] = glm::vec3(0.0f);
        if (particles.bodies.size() <= body) particles.bodies.resize(body + 1);
        return i;
    }

    // A slab of nx x ny x 2 particles (spacing s, h = 1.3 s) in the plane z = 0 facing the
    // camera, starting at `corner`; uv(column, row) gives each particle's uv.
    void slab(std::uint32_t body, glm::vec3 corner, int nx, int ny, float s,
              const std::function<glm::vec2(int, int)>& uv, glm::vec3 normal = {0, 0, 1}) {
        for (int layer = 0; layer < 2; ++layer)
            for (int y = 0; y < ny; ++y)
                for (int x = 0; x < nx; ++x)
                    add(body, corner + glm::vec3(x * s, y * s, -layer * s), 1.3f * s, uv(x, y),
                        normal);
    }

    void finish() {
        core::ParticleSet& ps = particles.particles;
        glm::dvec3 lo(std::numeric_limits<double>::max()),
            hi(std::numeric_limits<double>::lowest());
        for (std::size_t i = 0; i < ps.size(); ++i) {
            lo = glm::min(lo, glm::dvec3(ps.position[i]) - 2.0 * double(ps.h[i]));
            hi = glm::max(hi, glm::dvec3(ps.position[i]) + 2.0 * double(ps.h[i]));
        }
        particles.boundsMin = lo;
        particles.boundsMax = hi;
        for (std::uint32_t b = 0; b < particles.bodies.size(); ++b)
            particles.bodies[b].name = fmt::format("body{}", b);
    }
};

// Spheres of radius_scale * h (the analytic cases below), no shadows, smoothing or bloom.
inline Settings quiet() {
    Settings s;
    s.particles.radius = RadiusModel::Fixed;
    s.shadows = ShadowMode::None;
    s.ssss.enabled = false;
    s.bloom.enabled = false;
    return s;
}

struct Channels {
    const core::Image& image;
    float operator()(int x, int y, const char* name) const {
        return image.at(x, y, image.requireChannel(name));
    }
};

class RendererTest : public ::testing::Test {
  protected:
    gl::Context context{gl::ContextOptions{.debug = true}};  // any GL error fails the test
    Device device{context};  // every render of a test shares its programs and caches

    core::Frame render(TestScene& t, const Settings& settings) {
        t.finish();
        return Renderer(device, settings).render({t.scene, t.particles, t.materials});
    }
};

// A cube of (2 half + 1)^3 particles 0.2 apart, centred at (0.2 shift, 0, 0): the inner ones
// are hidden, so culling drops them.
inline TestScene cube(int half, float shift = 0.0f) {
    TestScene t;
    for (int z = -half; z <= half; ++z)
        for (int y = -half; y <= half; ++y)
            for (int x = -half; x <= half; ++x)
                t.add(0, glm::vec3(x + shift, y, z) * 0.2f, 0.26f,
                      {0.5f + 0.05f * x, 0.5f + 0.05f * y},
                      glm::normalize(glm::vec3(x, y, z) + glm::vec3(0.01f)));
    return t;
}

}  // namespace twinrender::realtime::testing
