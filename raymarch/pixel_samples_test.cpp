#include "raymarch/pixel_samples.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "core/frame.h"
#include "core/shading.h"

namespace twinrender::raymarch {
namespace {

core::Texture constant(glm::vec3 c) {
    core::Image image(1, 1, {"R", "G", "B"});
    for (int k = 0; k < 3; ++k) image.at(0, 0, k) = c[k];
    return core::Texture(std::move(image));
}

// A grey material that emits, under a light straight down -z.
struct Lit {
    std::vector<core::Material> materials;
    core::LightSettings light;
    Lit() {
        core::Material m;
        m.diffuse = constant(glm::vec3(0.5f));
        m.specular = constant(glm::vec3(0.0f));
        m.emission = constant({0.1f, 0.2f, 0.3f});
        m.cityLights = constant(glm::vec3(0.0f));
        materials.push_back(m);
        light.direction = {0.0, 0.0, -1.0};
        light.intensity = 2.0;
        light.color = {1.0, 1.0, 1.0};
        light.ambient = 0.05;
    }
};

SurfaceHit hitFacingUp(float depthTag = 0.0f) {
    SurfaceHit hit;
    hit.normal = {0.0f, 0.0f, 1.0f};
    hit.uv = {0.25f + depthTag, 0.5f};
    hit.body = 2;
    hit.glow = {0.01f, 0.0f, 0.0f};
    return hit;
}

TEST(PixelSamples, AHitFacingTheLightIsLitAndGlows) {
    const Lit s;
    const glm::dvec3 down(0.0, 0.0, -1.0);
    const ShadedSample lit = shadeHit(hitFacingUp(), down, 1.0f, s.materials, s.light);
    const ShadedSample dark = shadeHit(hitFacingUp(), down, 0.0f, s.materials, s.light);
    const glm::vec3 emission(0.11f, 0.2f, 0.3f);  // emission map + glow
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(lit.emission[k], emission[k], 1e-6f);
        // ambient 0.5 x 0.05, diffuse 0.5 x n.l 1 x intensity 2, the emission
        EXPECT_NEAR(lit.beauty[k], 0.025f + 1.0f + emission[k], 1e-6f);
        // In shadow: the ambient and the emission only.
        EXPECT_NEAR(dark.beauty[k], 0.025f + emission[k], 1e-6f);
    }
}

struct Pixel {
    core::Image aov = core::Image(2, 1, core::aov::channelNames());
    core::Image display = core::Image(2, 1, {"R", "G", "B"});
    AovChannels channels{aov};
    float at(const char* name) const { return aov.at(1, 0, aov.requireChannel(name)); }
};

TEST(PixelSamples, NoHitWritesTheBackground) {
    Pixel p;
    writePixel(PixelSamples{}, 4, 1.0f, 1, 0, p.channels, p.aov, p.display);
    const core::Image background = core::aov::makeImage(1, 1);
    for (int c = 0; c < background.channelCount(); ++c)
        EXPECT_EQ(p.aov.at(1, 0, c), background.at(0, 0, c)) << background.channelNames()[c];
    for (int k = 0; k < 3; ++k) EXPECT_EQ(p.display.at(1, 0, k), 0.0f);
}

// Two of four samples hit: beauty and coverage are means over the four, emission and shadow
// over the two hits; depth, normal, uv and id come from the hit nearest the pixel centre.
TEST(PixelSamples, SamplesAverageAndTheCentralHitGivesTheGeometry) {
    PixelSamples samples;
    const ShadedSample a{{0.4f, 0.8f, 1.2f}, {0.2f, 0.0f, 0.0f}};
    const ShadedSample b{{0.2f, 0.4f, 0.6f}, {0.0f, 0.2f, 0.0f}};
    samples.add(a, 1.0f, hitFacingUp(0.0f), 5.0, 0.9, 0.9);  // far from the centre
    samples.add(b, 0.0f, hitFacingUp(0.5f), 3.0, 0.6, 0.5);  // nearer: its geometry stays
    Pixel p;
    writePixel(samples, 4, 1.5f, 1, 0, p.channels, p.aov, p.display);
    const std::pair<const char*, float> expected[] = {
        {"R", 0.15f},         {"G", 0.3f},          {"B", 0.45f},         {"A", 0.5f},
        {"emission.R", 0.1f}, {"emission.G", 0.1f}, {"emission.B", 0.0f}, {"shadow", 0.5f},
        {"Z", 3.0f},          {"uv.U", 0.75f},      {"id", 2.0f},         {"N.Z", 1.0f}};
    for (const auto& [name, value] : expected) EXPECT_FLOAT_EQ(p.at(name), value) << name;
    // A later sample farther from the centre changes the geometry no more.
    samples.add(a, 1.0f, hitFacingUp(0.1f), 9.0, 0.5, 0.2);
    writePixel(samples, 4, 1.5f, 1, 0, p.channels, p.aov, p.display);
    EXPECT_EQ(p.at("Z"), 3.0f);
    EXPECT_EQ(p.at("uv.U"), 0.75f);
    // The display is the tonemapped beauty; the neighbour was not written.
    const glm::vec3 shown = core::tonemap({p.at("R"), p.at("G"), p.at("B")}, 1.5f);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(p.display.at(1, 0, k), shown[k]);
        EXPECT_EQ(p.display.at(0, 0, k), 0.0f);
    }
    EXPECT_EQ(p.aov.at(0, 0, p.aov.requireChannel("Z")), 0.0f);
}

}  // namespace
}  // namespace twinrender::raymarch
