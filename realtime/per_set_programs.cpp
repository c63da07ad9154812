// The programs of the per-set work on the GPU: which stage lives in which file, the variants a
// request compiles, and the check that the driver lays out the shared blocks as per_set_gpu.cpp
// reads and writes them.
#include <fmt/format.h>

#include <cassert>
#include <cstddef>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "realtime/gl/error.h"
#include "realtime/gpu_scene.h"
#include "realtime/occlusion_culling.h"
#include "realtime/per_set_gpu.h"
#include "realtime/per_set_layout.h"

namespace twinrender::realtime {

using namespace per_set_layout;

namespace {

// The file of shaders/ that holds a per-set stage (one #define each): per_set_<group>.comp.
const char* stageFile(std::string_view stage) {
    struct Group {
        const char* file;
        std::initializer_list<std::string_view> stages;
    };
    static const Group GROUPS[] = {
        {"per_set_grid.comp",
         {"INIT", "H_MIN", "LEVELS", "LAYOUT", "COUNT", "SCATTER", "SORT", "GATHER"}},
        {"per_set_radius.comp", {"INTERIOR", "RADIUS", "RADIUS_WALK", "INTERIOR_DRAWN"}},
        {"per_set_cull.comp", {"CULL_SPHERES", "CULL", "CULL_FULL"}},
        {"per_set_models.comp", {"NORMALS", "FIELD_NORMAL", "ANISOTROPY"}},
        {"per_set_droplets.comp",
         {"DROPLET_EDGES", "DROPLET_CLUSTERS", "DROPLET_LINKS", "DROPLET_FIT"}},
        {"per_set_pack.comp", {"NEAR_BOUND", "NEAR", "MARK", "PACK", "FINISH", "REPLACED"}},
    };
    for (const Group& g : GROUPS)
        if (std::ranges::find(g.stages, stage) != g.stages.end()) return g.file;
    assert(false && "a per-set stage without a file");
    return "per_set_grid.comp";
}

// A culling stage (CULL, CULL_FULL), the coarse grid's directions compiled in, and a variant's
// define (CULL: NEAR_MASKS, INTERIOR's near shells; CULL_FULL: CULL_PROBE, the probe) or "".
std::vector<std::string> cullDefines(const char* stage, const char* variant) {
    // The grid is symmetric: the 21 directions whose antipode comes later, then those
    // antipodes in the same order, so that one dot product tests a direction and its opposite.
    static const std::string directions = [] {
        const auto& d = cullingDirections().directions;
        std::vector<glm::dvec3> half, opposite;
        for (std::size_t k = 0; k < COARSE_DIRECTIONS; ++k)
            for (std::size_t m = k + 1; m < COARSE_DIRECTIONS; ++m)
                if (glm::length(d[k] + d[m]) < 1e-9) {
                    half.push_back(d[k]);
                    opposite.push_back(d[m]);
                }
        assert(2 * half.size() == COARSE_DIRECTIONS);
        half.insert(half.end(), opposite.begin(), opposite.end());
        std::string list;
        for (std::size_t k = 0; k < half.size(); ++k)
            list += fmt::format("{}vec3({:.9g}, {:.9g}, {:.9g})", k ? ", " : "", float(half[k].x),
                                float(half[k].y), float(half[k].z));
        return list;
    }();
    std::vector<std::string> defines = {stage, "COARSE_DIRECTION_VALUES " + directions};
    if (*variant) defines.emplace_back(variant);
    return defines;
}

}  // namespace

const gl::Program& per_set_layout::stageProgram(ProgramCache& programs, const char* stage) {
    return programs.compute(stageFile(stage), {stage});
}

const gl::Program& per_set_layout::cullProgram(ProgramCache& programs, const char* stage,
                                               const char* variant) {
    return programs.compute("per_set_cull.comp", cullDefines(stage, variant));
}

PerSetRequest perSetRequest(const Settings& settings) {
    PerSetRequest request;
    request.particles = settings.particles;
    // The culling test is exact for spheres only (renderer.cpp's uploadCpu says why).
    request.cull =
        settings.particles.cullHidden && settings.particles.shape == ParticleShape::Sphere;
    request.droplets = mayHaveDroplets(settings.particles);
    return request;
}

std::vector<ProgramVariant> perSetPrograms(const PerSetRequest& request) {
    std::vector<ProgramVariant> out;
    auto add = [&](const char* file, std::vector<std::string> defines) {
        out.push_back(ProgramVariant::computeProgram(file, std::move(defines)));
    };
    for (const char* stage : {"BLOCKS", "SUMS", "ADD"}) add("scan.comp", {stage});
    std::vector<const char*> stages = {"INIT",    "H_MIN",    "LEVELS", "LAYOUT",
                                       "COUNT",   "SCATTER",  "SORT",   "GATHER",
                                       "NORMALS", "INTERIOR", "RADIUS", "RADIUS_WALK",
                                       "MARK",    "PACK",     "FINISH", "INTERIOR_DRAWN"};
    if (request.cull) stages.insert(stages.end(), {"CULL_SPHERES", "NEAR_BOUND", "NEAR"});
    if (request.droplets)
        stages.insert(stages.end(),
                      {"DROPLET_EDGES", "DROPLET_CLUSTERS", "DROPLET_LINKS", "DROPLET_FIT"});
    // Frames that draw a body as one sphere count its drawn particles (GpuPerSet::countReplaced).
    if (request.particles.bodySpherePixels > 0.0) stages.push_back("REPLACED");
    const int kind = modelKind(request.particles);
    if (kind == 1) stages.push_back("FIELD_NORMAL");
    if (kind == 2) stages.push_back("ANISOTROPY");
    for (const char* stage : stages) add(stageFile(stage), {stage});
    if (request.cull)
        for (const auto& [stage, variant] :
             {std::pair{"CULL", request.particles.radius == RadiusModel::Field ? "NEAR_MASKS" : ""},
              {"CULL_FULL", "CULL_PROBE"},
              {"CULL_FULL", ""}})
            add("per_set_cull.comp", cullDefines(stage, variant));
    return out;
}

void checkPerSetLayouts(const gl::Program& program) {
    struct Expected {
        const char* name;
        std::size_t offset, stride;
    };
    static const Expected EXPECTED[] = {
        {"nearHit", 4, 0},
        {"dropletCount", DROPLET_COUNT * 4, 0},
        {"drawParticles", GpuPerSet::particleDrawOffset(), 0},
        {"levels[0].minX", LEVELS, 64},
        {"levels[0].hMaxBits", LEVELS + 28, 64},
        {"walkDispatch.groups", WALK_DISPATCH, 0},
        {"walkDispatch.entries", WALK_DISPATCH + 12, 0},
        {"nextWalkDispatch.groups", NEXT_WALK_DISPATCH, 0},
        {"scanDispatch", SCAN_DISPATCH, 0},
        {"sortDispatch", SORT_DISPATCH, 0},
        {"nearDispatch", NEAR_DISPATCH, 0},
        {"usedLevels", USED_LEVELS, 0},
        {"levelList[0]", USED_LEVELS + 4, 0},
        {"levelCoefficientMin[0]", USED_LEVELS + 4 + MAX_LEVELS * 4, 0},
        {"sparseDispatch.groups", SPARSE_DISPATCH, 0},
        {"drawDroplets", DROPLET_DRAW, 0},
        {"particles[0].positionRadius", 0, sizeof(GpuParticle)},
        {"particles[0].hessianOffDiagonal", offsetof(GpuParticle, hessianOffDiagonal),
         sizeof(GpuParticle)},
    };
    for (const Expected& e : EXPECTED) {
        const auto found = program.bufferVariable(e.name);
        if (!found) continue;  // not active in this stage
        if (found->offset != static_cast<long long>(e.offset) ||
            (e.stride != 0 && found->topLevelStride != static_cast<long long>(e.stride)))
            throw gl::Error(fmt::format(
                "program '{}': the driver lays out '{}' at byte {} (array stride {}), "
                "per_set_gpu.cpp expects byte {} (stride {})",
                program.name(), e.name, found->offset, found->topLevelStride, e.offset, e.stride));
    }
}

void compilePerSetPrograms(ProgramCache& programs, const PerSetRequest& request) {
    for (const ProgramVariant& v : perSetPrograms(request)) checkPerSetLayouts(v.build(programs));
    timerQueriesSeeCompute(programs);  // set-up, not a frame's work: the stages' clock
}

}  // namespace twinrender::realtime
