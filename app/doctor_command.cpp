#include "app/doctor_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "realtime/gl/context.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gl/poison.h"
#include "realtime/gpu_scene.h"
#include "realtime/per_set_gpu.h"
#include "realtime/program_variants.h"
#include "realtime/self_check.h"

namespace twinrender::app {

namespace {

// A limit the renderer needs: the device's value and the least the renderer works with.
struct Limit {
    const char* name;
    long long value, needed;
    const char* why;
};

std::vector<Limit> limits(const realtime::gl::Limits& l, const LoadedScene& s) {
    const std::size_t n = s.particles.particles.size();
    const realtime::Settings& r = s.realtime;
    const long long image = std::max(s.scene.camera.width, s.scene.camera.height);
    return {
        {"GL_MAX_TEXTURE_SIZE", l.maxTextureSize,
         std::max<long long>(image,
                             realtime::usesShadowMap(r.shadows) ? r.shadowMap.resolution : 0),
         "the image and the shadow map"},
        {"GL_MAX_SHADER_STORAGE_BLOCK_SIZE", l.maxStorageBlockBytes,
         static_cast<long long>(n * sizeof(realtime::GpuParticle)), "the scene's packed particles"},
        {"GL_MAX_TEXTURE_BUFFER_SIZE", l.maxTextureBufferTexels,
         static_cast<long long>(realtime::perSetTexels(n)), "the scene's per-set grid"},
        {"GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS", l.maxStorageBindings, 23,
         "the per-set stages' bindings 0-22"},
        {"GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS", l.maxComputeStorageBlocks, 10,
         "PACK's storage blocks"},
        {"GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS", l.maxComputeTextureUnits, 13,
         "the walks' buffer textures, units 8-12"},
        {"GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS", l.maxComputeInvocations, 256,
         "scan.comp's work group"},
        {"GL_MAX_COMPUTE_SHARED_MEMORY_SIZE", l.maxComputeSharedBytes, 1024,
         "scan.comp's shared sums"},
        {"GL_MAX_DRAW_BUFFERS", l.maxDrawBuffers, 3, "the G-buffer's targets"},
    };
}

}  // namespace

ExitCode selfCheckScene(const LoadedScene& s, Devices& devices) {
    const realtime::SelfCheck check =
        realtime::selfCheck(devices.realtime(), s.realtime, {s.scene, s.particles, s.materials});
    std::printf("self-check of %s (per_set cpu against gpu, %dx%d, %zu particles):\n%s",
                s.scene.name.c_str(), s.scene.camera.width, s.scene.camera.height,
                s.particles.particles.size(), check.table().c_str());
    std::printf("self-check: %s\n", check.passed() ? "pass" : "FAIL");
    std::fflush(stdout);
    return check.passed() ? ExitCode::Pass : ExitCode::Fail;
}

ExitCode runDoctor(const DoctorOptions& o) {
    // The scene first: bad input is said before anything runs.
    std::vector<std::string> sets = {"camera.width=160", "camera.height=120"};
    sets.insert(sets.end(), o.sets.begin(), o.sets.end());
    const LoadedScene scene = loadScene(o.scene, sets);
    Devices devices(o.requireGpu);
    const realtime::gl::Context& context = devices.glContext();
    std::printf("device: %s\n", context.description().c_str());
    std::printf("GL_VENDOR: %s\nGL_VERSION: %s\n", context.vendor().c_str(),
                context.version().c_str());
    for (const std::string& skipped : context.skipped())
        std::printf("  skipped: %s\n", skipped.c_str());
    if (realtime::gl::poisonMode()) std::printf("poison mode: on (TWINRENDER_GL_POISON)\n");
    bool pass = true;

    std::printf("\nlimits (the device's; what the renderer needs for %s):\n",
                scene.scene.name.c_str());
    for (const Limit& l : limits(realtime::gl::queryLimits(), scene)) {
        const bool ok = l.value >= l.needed;
        pass = pass && ok;
        std::printf("  %-38s %12lld  needs %12lld  %s  (%s)\n", l.name, l.value, l.needed,
                    ok ? "ok" : "SHORT", l.why);
    }

    const std::vector<realtime::ProgramVariant> variants = realtime::allProgramVariants();
    realtime::ProgramCache programs;
    const std::vector<realtime::CompileFailure> failures =
        realtime::compileEach(programs, variants);
    std::printf("\nprograms: %zu variants, %zu compiled, %zu failed\n", variants.size(),
                variants.size() - failures.size(), failures.size());
    for (const realtime::CompileFailure& f : failures)
        std::printf("  %s\n%s\n", f.program.c_str(), f.log.c_str());
    pass = pass && failures.empty();

    std::printf("\n");
    std::fflush(stdout);
    if (failures.empty()) {
        pass = selfCheckScene(scene, devices) == ExitCode::Pass && pass;
        const realtime::SelfCheck stages = realtime::perSetStageCheck(
            scene.particles, scene.realtime, scene.scene.camera.position);
        std::printf("\nper-set stages alone (GpuPerSet against the CPU functions):\n%s",
                    stages.table().c_str());
        std::printf("per-set stages: %s\n", stages.passed() ? "pass" : "FAIL");
        pass = pass && stages.passed();
    } else {
        std::printf("self-check: not run (programs do not compile)\n");
    }
    std::printf("\nverdict: %s\n", pass ? "pass" : "FAIL");
    return pass ? ExitCode::Pass : ExitCode::Fail;
}

}  // namespace twinrender::app
