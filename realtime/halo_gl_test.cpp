// The sub-pixel emitters' halo (realtime.particles.halo_pixels) on llvmpipe: one glowing sphere
// a fraction of a pixel across on black. The halo carries its flux wherever it lies; a nearer
// surface hides it; a sphere above the threshold is drawn as without a halo.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "realtime/testing/gl_test_scene.h"

namespace twinrender::realtime {
namespace {

using testing::constantTexture;
using testing::HEIGHT;
using testing::quiet;
using testing::RendererTest;
using testing::TestScene;
using testing::WIDTH;

const glm::vec3 HALO_RADIANCE(2.0f, 1.0f, 0.5f);
constexpr float HALO_H = 0.1f;  // the particle's h: a sphere of radius_scale h

// One glowing particle on black at `centre`, seen from (0, 0, 10) (no sun, no ambient light);
// with `occluderZ`, a grey particle of h = 0.5 at that z on the line of sight.
TestScene glowingParticle(glm::vec3 centre, std::optional<float> occluderZ = std::nullopt) {
    TestScene t;
    t.scene.light.intensity = 0.0;
    t.scene.light.ambient = 0.0;
    core::Material glowing = t.materials[0];
    glowing.diffuse = constantTexture(glm::vec3(0.0f));
    glowing.emission = constantTexture(HALO_RADIANCE);
    t.materials.push_back(glowing);
    t.particles.particles.material[t.add(0, centre, HALO_H)] = 1;
    if (occluderZ) t.add(1, glm::vec3(centre.x, centre.y, *occluderZ), 0.5f);
    return t;
}

// The image's summed linear beauty (the flux, in pixel areas times radiance), per channel.
glm::dvec3 flux(const core::Frame& frame) {
    const core::Image& im = frame.image;
    const int channels[3] = {im.requireChannel("R"), im.requireChannel("G"),
                             im.requireChannel("B")};
    glm::dvec3 sum(0.0);
    for (int y = 0; y < im.height(); ++y)
        for (int x = 0; x < im.width(); ++x)
            for (int c = 0; c < 3; ++c) sum[c] += im.at(x, y, channels[c]);
    return sum;
}

// The flux of a sphere of radius r at eye depth z: its projected area in pixels, pi rho^2,
// rho = r * pixels per unit (core::Camera::pixelsPerUnitAt), times its radiance.
glm::dvec3 sphereFlux(const TestScene& t, double r, double z) {
    const double rho =
        r * 0.5 * HEIGHT / (std::tan(0.5 * t.scene.camera.fovYDeg * std::numbers::pi / 180.0) * z);
    return std::numbers::pi * rho * rho * glm::dvec3(HALO_RADIANCE);
}

class Halo : public RendererTest {};

TEST_F(Halo, CarriesTheSpheresFluxWhereverItLies) {
    Settings halo = quiet();
    halo.particles.haloPixels = 1.0;
    // The sphere (r = 0.09) is 1.51 px in radius at eye depth 10; at 50, 0.30 px, moved by
    // fifths of a pixel (0.298 units there) right and up.
    const double pixel = 2.0 * std::tan(15.0 * std::numbers::pi / 180.0) * 50.0 / HEIGHT;
    for (int k = 0; k < 5; ++k) {
        const float shift = static_cast<float>(0.2 * k * pixel);
        TestScene t = glowingParticle({shift, 0.7f * shift, -40.0f});
        const glm::dvec3 expected = sphereFlux(t, 0.9 * HALO_H, 50.0);
        const glm::dvec3 drawn = flux(render(t, halo));
        // The Gaussian (sigma 0.7 px) sampled at the pixel centres sums to 1 within 0.03 %
        // wherever it lies (Poisson summation: 2 exp(-2 pi^2 sigma^2) an axis), and its tail
        // beyond 4 sigma holds 0.03 %; float sums of a few hundred terms add nothing near that.
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(drawn[c] / expected[c], 1.0, 2e-3) << "shift " << k << "/5, channel " << c;
        // Without the halo the sphere covers one pixel centre or none.
        if (k == 0) {
            TestScene plain = glowingParticle({shift, 0.7f * shift, -40.0f});
            EXPECT_LT(flux(render(plain, quiet())).x, 0.5 * expected.x);
        }
    }
}

TEST_F(Halo, ANearerSurfaceHidesIt) {
    Settings halo = quiet();
    halo.particles.haloPixels = 1.0;
    // The grey occluder reflects nothing (no light): in front of the sphere every pixel is black.
    TestScene front = glowingParticle({0.0f, 0.0f, -40.0f}, 5.0f);
    EXPECT_EQ(flux(render(front, halo)), glm::dvec3(0.0));
    // Behind it (eye depth 60) the occluder hides nothing: the halo carries the sphere's flux as
    // on black (within 2e-3, as above), where the sphere drawn without one gives less than half
    // of it (CarriesTheSpheresFluxWhereverItLies). So a halo option doing nothing fails here.
    TestScene behind = glowingParticle({0.0f, 0.0f, -40.0f}, -50.0f);
    const glm::dvec3 expected = sphereFlux(behind, 0.9 * HALO_H, 50.0);
    const glm::dvec3 drawn = flux(render(behind, halo));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(drawn[c] / expected[c], 1.0, 2e-3) << "channel " << c;
}

TEST_F(Halo, ASphereAboveTheThresholdIsDrawnAsWithout) {
    // At eye depth 10 the sphere is 1.51 px in radius: above a threshold of 1.
    Settings halo = quiet();
    halo.particles.haloPixels = 1.0;
    TestScene a = glowingParticle({0.0f, 0.0f, 0.0f}), b = glowingParticle({0.0f, 0.0f, 0.0f});
    const core::Frame on = render(a, halo), off = render(b, quiet());
    ASSERT_EQ(on.image.pixels().size(), off.image.pixels().size());
    EXPECT_TRUE(
        std::equal(on.image.pixels().begin(), on.image.pixels().end(), off.image.pixels().begin()));
}

}  // namespace
}  // namespace twinrender::realtime
