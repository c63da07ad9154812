#include "core/shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/mat4x4.hpp>
#include <string>

#include "core/camera.h"

namespace tc = twinrender::core;

namespace {
std::vector<tc::Material> oneMaterial(double diffuse, double specular, double city) {
    tc::Scene scene;
    tc::MaterialDesc m;
    m.name = std::string(1, 'm');  // a literal assignment trips GCC 12's -Wrestrict (PR 105329)
    m.diffuse.value = glm::dvec3(diffuse);
    m.specular.value = glm::dvec3(specular);
    m.cityLights.value = glm::dvec3(city);
    m.shininess = 16.0;
    scene.materials.push_back(m);
    return tc::loadMaterials(scene);
}
}  // namespace

TEST(Shading, LambertAmbientShadowAndCityLights) {
    const auto mats = oneMaterial(0.5, 0.0, 2.0);
    tc::LightSettings light;
    light.direction = {0.0, 0.0, -1.0};
    light.intensity = 2.0;
    light.color = {1.0, 1.0, 1.0};
    light.ambient = 0.1;
    tc::SurfacePoint p;
    p.normal = {0.0f, 0.0f, 1.0f};
    p.toEye = {0.0f, 0.0f, 1.0f};
    p.uv = {0.5f, 0.5f};
    // Facing the sun: albedo * (intensity * cos + ambient).
    EXPECT_NEAR(tc::shade(mats, light, p).x, 0.5 * (2.0 * 1.0 + 0.1), 1e-6);
    // 60 degrees off: cos = 0.5.
    p.normal = {std::sqrt(0.75f), 0.0f, 0.5f};
    EXPECT_NEAR(tc::shade(mats, light, p).x, 0.5 * (2.0 * 0.5 + 0.1), 1e-5);
    // In shadow: ambient only.
    p.visibility = 0.0f;
    EXPECT_NEAR(tc::shade(mats, light, p).x, 0.5 * 0.1, 1e-6);
    // Night side: ambient plus the city lights.
    p.visibility = 1.0f;
    p.normal = {0.0f, 0.0f, -1.0f};
    EXPECT_NEAR(tc::shade(mats, light, p).x, 0.5 * 0.1 + 2.0, 1e-6);
    EXPECT_FLOAT_EQ(tc::nightFactor({0, 0, 1}, {0, 0, 1}), 0.0f);
    EXPECT_FLOAT_EQ(tc::nightFactor({1, 0, 0}, {0, 0, 1}), 0.5f);  // the terminator
    // Light from emitting surfaces, irradiance E: the Lambert reflection albedo E / pi, on the
    // night side as anywhere (no city lights here).
    const auto plain = oneMaterial(0.5, 0.0, 0.0);
    p.irradiance = {3.0f, 0.0f, 6.0f};
    const glm::vec3 lit = tc::shade(plain, light, p);
    EXPECT_NEAR(lit.x, 0.5 * 0.1 + 0.5 * 3.0 / M_PI, 1e-6);
    EXPECT_NEAR(lit.y, 0.5 * 0.1, 1e-6);
    EXPECT_NEAR(lit.z, 0.5 * 0.1 + 0.5 * 6.0 / M_PI, 1e-6);
}

// The specular term is unnormalised Blinn-Phong: specular x (n.h)^shininess x the light's
// colour x intensity x visibility, with no n.l factor, wherever n.l > 0. Expected values written
// by hand from that formula (shininess 16, material specular 0.5, light 2 x (1, 0.5, 0.25)).
TEST(Shading, SpecularFollowsBlinnPhongAtTheHalfVector) {
    const auto mats = oneMaterial(0.0, 0.5, 0.0);  // no diffuse: the specular term alone
    const double deg = M_PI / 180.0;
    // Light and eye in the xz plane at angles a and b from the normal (0, 0, 1), on one side:
    // the half vector lies at (a + b) / 2 from the normal.
    const auto at = [](double angle) {
        return glm::vec3(float(std::sin(angle)), 0.0f, float(std::cos(angle)));
    };
    tc::LightSettings light;
    light.intensity = 2.0;
    light.color = {1.0, 0.5, 0.25};
    light.ambient = 0.0;
    tc::SurfacePoint p;
    p.normal = {0.0f, 0.0f, 1.0f};
    p.uv = {0.5f, 0.5f};

    // n = h (light 20 degrees to one side, eye 20 to the other): the peak, 0.5 x 2 = 1 times the
    // light's colour; n.l = 0.94 does not enter.
    light.direction = -glm::dvec3(at(20.0 * deg));
    p.toEye = at(-20.0 * deg);
    const glm::vec3 peak = tc::shade(mats, light, p);
    EXPECT_NEAR(peak.r, 1.0, 1e-6);
    EXPECT_NEAR(peak.g, 0.5, 1e-6);
    EXPECT_NEAR(peak.b, 0.25, 1e-6);

    // Light at 10 degrees, eye at 50: h at 30 degrees from n, cos(30)^16 = (3/4)^8 =
    // 6561 / 65536 = 0.100112915...
    light.direction = -glm::dvec3(at(10.0 * deg));
    p.toEye = at(50.0 * deg);
    const double lobe = 6561.0 / 65536.0;
    // Float directions and a float pow: a relative 1e-6 (16 x the cosine's rounding of 6e-8).
    EXPECT_NEAR(tc::shade(mats, light, p).r, 1.0 * lobe, 1e-6 * lobe);
    EXPECT_NEAR(tc::shade(mats, light, p).b, 0.25 * lobe, 1e-6 * lobe);
    // The shadow scales it; the diffuse term adds albedo x n.l x 2.
    p.visibility = 0.25f;
    EXPECT_NEAR(tc::shade(mats, light, p).r, 0.25 * lobe, 1e-6 * lobe);
    p.visibility = 1.0f;
    const auto lit = oneMaterial(0.4, 0.5, 0.0);
    EXPECT_NEAR(tc::shade(lit, light, p).r, 0.4 * std::cos(10.0 * deg) * 2.0 + lobe, 1e-6);

    // The light just below the horizon (95 degrees, n.l < 0) gives no highlight, though with the
    // eye at -60 degrees h lies 17.5 degrees from n, where the lobe would be 0.47.
    light.direction = -glm::dvec3(at(95.0 * deg));
    p.toEye = at(-60.0 * deg);
    EXPECT_EQ(tc::shade(mats, light, p), glm::vec3(0.0f));
}

TEST(Shading, TonemapAndSrgb) {
    // sRGB transfer function: published values.
    EXPECT_NEAR(tc::linearToSrgb(0.0031308f), 0.04045f, 1e-5f);
    EXPECT_NEAR(tc::linearToSrgb(0.18f), 0.4614f, 1e-4f);
    EXPECT_NEAR(tc::srgbToLinear(tc::linearToSrgb(0.3f)), 0.3f, 1e-6f);
    // ACES fit (Narkowicz): 0 -> 0, monotone, saturates below 1 for large inputs.
    EXPECT_FLOAT_EQ(tc::tonemap({0, 0, 0}, 1.0f).x, 0.0f);
    const float a = tc::tonemap({0.5f, 0, 0}, 1.0f).x, b = tc::tonemap({1.0f, 0, 0}, 1.0f).x;
    EXPECT_LT(a, b);
    // x = 1: (2.51 + 0.03) / (2.43 + 0.59 + 0.14) = 0.80380..., then sRGB-encoded.
    EXPECT_NEAR(b, tc::linearToSrgb(2.54f / 3.16f), 1e-6f);
    EXPECT_NEAR(tc::tonemap({1e6f, 0, 0}, 1.0f).x, 1.0f, 1e-3f);
    EXPECT_FLOAT_EQ(tc::tonemap({0.5f, 0, 0}, 2.0f).x, b);  // exposure scales first
}

TEST(Camera, RaysProjectionAndDepth) {
    tc::CameraSettings s;
    s.position = {0.0, -5.0, 0.0};
    s.target = {0.0, 0.0, 0.0};
    s.up = {0.0, 0.0, 1.0};
    s.fovYDeg = 90.0;
    s.width = 200;
    s.height = 100;
    const tc::Camera cam(s);
    const tc::Ray centre = cam.ray(100.0, 50.0);
    EXPECT_NEAR(centre.direction.y, 1.0, 1e-12);
    // Top edge of a 90-degree field of view: 45 degrees up.
    const tc::Ray top = cam.ray(100.0, 0.0);
    EXPECT_NEAR(top.direction.z, std::sqrt(0.5), 1e-12);
    // Right edge: aspect 2, so tan = 2.
    const tc::Ray right = cam.ray(200.0, 50.0);
    EXPECT_NEAR(right.direction.x / right.direction.y, 2.0, 1e-12);
    // Projection inverts the ray; eye depth is along the axis.
    const glm::dvec3 p = cam.position() + 3.0 * cam.ray(37.25, 81.5).direction;
    const glm::dvec2 px = cam.project(p);
    EXPECT_NEAR(px.x, 37.25, 1e-9);
    EXPECT_NEAR(px.y, 81.5, 1e-9);
    EXPECT_NEAR(cam.eyeDepth({4.0, 2.0, -1.0}), 7.0, 1e-12);
    // The view matrix maps the camera to the origin, looking down -z.
    const glm::dvec4 v = cam.viewMatrix() * glm::dvec4(0.0, 0.0, 0.0, 1.0);
    EXPECT_NEAR(v.z, -5.0, 1e-12);
}
