// Every program the renderer can build compiles on this device, and a frame builds none that
// set-up did not compile (programVariants lists what the passes use).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "realtime/gl/context.h"
#include "realtime/gl/pipeline.h"
#include "realtime/program_variants.h"
#include "realtime/testing/gl_test_scene.h"

namespace twinrender::realtime {
namespace {

TEST(ProgramVariants, EveryVariantCompiles) {
    gl::Context context;
    ProgramCache programs;
    const std::vector<ProgramVariant> variants = allProgramVariants();
    EXPECT_GT(variants.size(), 60u);
    for (const CompileFailure& f : compileEach(programs, variants))
        ADD_FAILURE() << f.program << "\n" << f.log;
    EXPECT_EQ(programs.size(), variants.size());
}

// The per-set stages declare every shared storage block (shaders/per_set_stages.glsl); a stage
// uses at most 10 of them (doctor's GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS line), within NVIDIA's
// 16 and the device's limit: a block declared and not used must not count.
TEST(ProgramVariants, PerSetStagesUseAtMostTenStorageBlocks) {
    gl::Context context;
    ProgramCache programs;
    int most = 0;
    for (const ProgramVariant& v : allProgramVariants()) {
        if (!v.compute.starts_with("per_set_")) continue;
        const int blocks = v.build(programs).activeStorageBlocks();
        EXPECT_LE(blocks, 10) << v.name();
        most = std::max(most, blocks);
    }
    EXPECT_LE(most, gl::queryLimits().maxComputeStorageBlocks);
    EXPECT_EQ(most, 10) << "doctor's line names the most a stage uses";
}

using testing::RendererTest;
using testing::TestScene;

// What a frame with each of these settings compiles is among programVariants(settings).
TEST_F(RendererTest, AFrameBuildsOnlyTheProgramsItsSettingsList) {
    TestScene t;
    t.slab(0, {-1.0f, -1.0f, 0.0f}, 8, 8, 0.25f,
           [](int x, int y) { return glm::vec2(x / 8.0f, y / 8.0f); });
    t.finish();
    std::vector<Settings> cases(6);
    cases[1].particles.shape = ParticleShape::Ellipsoid;
    cases[1].shadows = ShadowMode::Pcf;
    cases[2].surface.method = SurfaceMethod::NarrowRange;
    cases[2].depth = DepthMode::Reversed;
    cases[3].particles.normal = NormalModel::Field;
    cases[3].shadows = ShadowMode::Spheres;
    cases[3].perSet = PerSetDevice::Cpu;
    cases[4].surface.method = SurfaceMethod::Bilateral;
    cases[4].depth = DepthMode::Standard;
    cases[4].ao.method = AoMethod::Traced;
    cases[5].particles.radius = RadiusModel::Fixed;
    cases[5].bloom.enabled = false;
    cases[5].perSet = PerSetDevice::Cpu;
    cases[5].particles.bodySpherePixels = 4096.0;  // the slab drawn as one sphere
    for (const Settings& s : cases) {
        Device device(context);
        Renderer renderer(device, s);
        renderer.render({t.scene, t.particles, t.materials});
        std::vector<std::string> listed;
        for (const ProgramVariant& v : programVariants(s, false)) listed.push_back(v.name());
        for (const std::string& built : device.programNames())
            EXPECT_NE(std::find(listed.begin(), listed.end(), built), listed.end()) << built;
    }
}

}  // namespace
}  // namespace twinrender::realtime
