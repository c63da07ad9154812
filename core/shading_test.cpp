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
