#include "core/stage_table.h"

#include <algorithm>
#include <array>

namespace twinrender::core {

namespace {
// clang-format off
constexpr std::array STAGES = {
    StageInfo{.key = "total", .renderer = "both", .cadence = StageCadence::Frame,
              .meaning = "the frame, from the upload to the read-back (compiling excluded)"},
    StageInfo{.key = "compile", .renderer = "realtime", .cadence = StageCadence::Setup,
              .meaning = "the programs compiled for these settings (once per device)"},
    StageInfo{.key = "upload", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "the frame's uniforms, materials and particle records to the device"},
    StageInfo{.key = "grid", .renderer = "realtime", .cadence = StageCadence::Set,
              .meaning = "per_set = gpu: the neighbour grid, by counting sort"},
    StageInfo{.key = "particle_normals", .renderer = "realtime", .cadence = StageCadence::Set,
              .meaning = "the particle normals, where a set came without them"},
    StageInfo{.key = "radius", .renderer = "realtime", .cadence = StageCadence::Set,
              .meaning = "the impostor radii (the level set along the normal)"},
    StageInfo{.key = "droplets", .renderer = "realtime", .cadence = StageCadence::Set,
              .meaning = "the small droplets' ellipsoids"},
    StageInfo{.key = "kernels", .renderer = "realtime", .cadence = StageCadence::Set,
              .meaning = "per_set = cpu: the kernels the gradient pass splats"},
    StageInfo{.key = "field_normals", .renderer = "realtime", .cadence = StageCadence::Set,
              .meaning = "the field normal models (normal = field)"},
    StageInfo{.key = "anisotropy", .renderer = "realtime", .cadence = StageCadence::Set,
              .meaning = "the anisotropic ellipsoids (shape = ellipsoid)"},
    StageInfo{.key = "cull", .renderer = "realtime", .cadence = StageCadence::Set,
              .meaning = "the occlusion culling of hidden spheres"},
    StageInfo{.key = "pack", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "per_set = gpu: the drawn particles marked and packed"},
    StageInfo{.key = "shadow", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "the shadow map (and its moments and blur)"},
    StageInfo{.key = "gbuffer", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "the impostors into the G-buffer"},
    StageInfo{.key = "normals", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "the gradient normals (normal = gradient)"},
    StageInfo{.key = "ssss", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "screen-space surface smoothing"},
    StageInfo{.key = "surface", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "a depth filter (surface.method) and its rebuilt normals"},
    StageInfo{.key = "ao", .renderer = "both", .cadence = StageCadence::Frame,
              .meaning = "ambient occlusion: the screen-space pass and its blur, or the "
                         "reference's occlusion rays"},
    StageInfo{.key = "emissive", .renderer = "both", .cadence = StageCadence::Frame,
              .meaning = "the light of emitting surfaces (light.emissive_light): the real-time "
                         "estimate (emissive.method), or the reference's rays toward the emitters"},
    StageInfo{.key = "shade", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "the lighting of every covered pixel"},
    StageInfo{.key = "halo", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "sub-pixel emitters' flux as Gaussian halos (particles.halo_pixels)"},
    StageInfo{.key = "atmosphere", .renderer = "both", .cadence = StageCadence::Frame,
              .meaning = "a body's atmosphere (bodies[].atmosphere): the real-time pass from its "
                         "end point (atmosphere.end_point), or the reference's from the exact hit"},
    StageInfo{.key = "post", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "glow, bloom and tonemapping"},
    StageInfo{.key = "readback", .renderer = "realtime", .cadence = StageCadence::Frame,
              .meaning = "the AOV and display buffers back to the CPU, assembled"},
    StageInfo{.key = "build", .renderer = "raymarch", .cadence = StageCadence::Frame,
              .meaning = "the Embree scene and the neighbour grids"},
    StageInfo{.key = "trace", .renderer = "raymarch", .cadence = StageCadence::Frame,
              .meaning = "the camera rays, and the shadow rays of a point sun"},
    StageInfo{.key = "sun", .renderer = "raymarch", .cadence = StageCadence::Frame,
              .meaning = "the shadow rays over the sun's disc (light.angular_radius > 0)"},
};
// clang-format on
}  // namespace

std::span<const StageInfo> stageTable() {
    return STAGES;
}

const StageInfo* findStage(std::string_view key) {
    const auto it = std::find_if(STAGES.begin(), STAGES.end(),
                                 [&](const StageInfo& s) { return s.key == key; });
    return it == STAGES.end() ? nullptr : &*it;
}

std::vector<std::string> inStageOrder(std::vector<std::string> stages) {
    auto rank = [](const std::string& s) {
        const StageInfo* info = findStage(s);
        return info ? info - STAGES.data() : static_cast<std::ptrdiff_t>(STAGES.size());
    };
    std::stable_sort(stages.begin(), stages.end(), [&](const std::string& a, const std::string& b) {
        const auto ra = rank(a), rb = rank(b);
        return ra != rb ? ra < rb : a < b;
    });
    return stages;
}

}  // namespace twinrender::core
