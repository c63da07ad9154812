#include "realtime/gpu_scene.h"

#include <gtest/gtest.h>

#include "realtime/impostor_radius.h"

namespace twinrender::realtime {
namespace {

TEST(GpuScene, PacksParticlesCameraRelative) {
    core::ParticleSet ps;
    ps.resize(2);
    ps.position = {{1e6f, 2.0f, 3.0f}, {1e6f + 1.0f, 2.0f, 3.0f}};
    ps.h = {0.5f, 1.0f};
    ps.body = {0, 7};
    ps.material = {1, 2};
    ps.uv = {{0.25f, 0.75f}, {0.5f, 0.5f}};
    const std::uint32_t second[] = {1};
    const auto all = packParticles(ps, glm::dvec3(1e6, 0.0, 0.0), fixedRadii(ps, 2.0));
    ASSERT_EQ(all.size(), 2u);
    EXPECT_EQ(all[0].positionRadius, glm::vec4(0.0f, 2.0f, 3.0f, 1.0f));
    EXPECT_EQ(all[1].positionRadius.x, 1.0f);
    EXPECT_EQ(all[0].normalU.w, 0.25f);
    EXPECT_EQ(all[0].dudxV.w, 0.75f);
    EXPECT_EQ(all[1].dvdxBody.w, 7.0f);
    EXPECT_EQ(all[1].glowMaterial.w, 2.0f);
    const auto some = packParticles(ps, glm::dvec3(1e6, 0.0, 0.0), fixedRadii(ps, 2.0), second);
    ASSERT_EQ(some.size(), 1u);
    EXPECT_EQ(some[0].dvdxBody.w, 7.0f);
}

TEST(GpuScene, StoresIdenticalTexturesOnce) {
    core::Image grey(1, 1, {"R", "G", "B"});
    grey.fillChannel(0, 0.5f);
    core::Image big(4, 2, {"R", "G", "B"});
    big.at(3, 1, 2) = 1.0f;
    core::Material a;
    a.diffuse = core::Texture(big);
    a.specular = core::Texture(grey);
    a.emission = core::Texture(grey);
    a.cityLights = core::Texture(big);
    a.shininess = 8.0f;
    const GpuMaterials g = packMaterials({a, a});
    EXPECT_EQ(g.texels.size(), 3u * (8 + 1));
    ASSERT_EQ(g.records.size(), 2u);
    EXPECT_EQ(g.records[0].diffuse, glm::ivec4(0, 4, 2, 0));
    EXPECT_EQ(g.records[0].specular, glm::ivec4(8, 1, 1, 0));  // offsets count texels
    EXPECT_EQ(g.records[1].cityLights, g.records[0].diffuse);
    EXPECT_EQ(g.texels[3 * 7 + 2], 1.0f);
    EXPECT_EQ(g.records[0].params.x, 8.0f);
}

TEST(GpuScene, StoresSingleColourTexturesAsOneTexel) {
    core::Image flat(16, 8, {"R", "G", "B"});
    flat.fillChannel(1, 0.25f);
    core::Material m;
    m.diffuse = m.specular = m.emission = m.cityLights = core::Texture(flat);
    const GpuMaterials g = packMaterials({m});
    EXPECT_EQ(g.texels, (std::vector<float>{0.0f, 0.25f, 0.0f}));
    EXPECT_EQ(g.records[0].diffuse, glm::ivec4(0, 1, 1, 0));
}

}  // namespace
}  // namespace twinrender::realtime
