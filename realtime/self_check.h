// The per-set self-check: a scene rendered through both per-set paths (per_set = "cpu" and
// "gpu", every other setting the same) on one device, their counters and images compared, so
// that a driver bug or a new shader bug shows as a failed check, never as a silently wrong
// report. `twinrender doctor` runs it, and `render` / `run` with --self-check.
#pragma once

#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "core/renderer.h"
#include "realtime/renderer.h"
#include "realtime/settings.h"

namespace twinrender::realtime {

struct SelfCheck {
    struct Check {
        std::string name{};  // "particles_drawn", "coverage_or_body_apart", ...
        double cpu = 0.0;    // the value on the CPU path (for the counters)
        double gpu = 0.0;    // the value on the GPU path; for the images, the measure itself
        double bound = 0.0;  // the largest difference (or measure) that passes
        bool pass = false;
        std::string why{};  // what the bound allows, in words
        // perSetStageCheck: the stage whose records or answers this check reads ("upload",
        // "levels", "layout", "grid", "radius", "cull", "draw_list"), and where a failed check
        // found its first difference (the particle, level or slot, both values).
        std::string stage{};
        std::string first{};
    };
    std::vector<Check> checks;
    // What a failed check found, for whoever mends it (the first particles apart, ...).
    std::vector<std::string> notes;
    bool passed() const;
    // One line per check, then the notes.
    std::string table() const;
};

// Renders `input` with `settings` through both per-set paths on `device` and compares:
// particles_drawn within 3 (the radii agree within 3e-4 h, so a sphere or two may change sides
// of the culling test), droplets equal; pixels whose coverage or body differ, and covered pixels
// whose red differs by more than 1e-2, each at most 1 in 200 of the covered pixels (outline pixels
// of spheres whose radius moved, as per_set_gpu_gl_test.cpp measures).
SelfCheck selfCheck(Device& device, const Settings& settings, const core::RenderInput& input);

// The per-set stages alone (GpuPerSet, as BM_PerSet1MGpu runs them, no render passes) against
// the CPU functions on the same particles (their normals derived on the CPU first, droplets
// left out): radii within 3e-4 h (no particle beyond), the spheres the culling leaves visible
// (at most 1 in 200 hidden on the GPU only, 1 in 100 on the CPU only: both tests are exact with
// a margin), and the drawn count after pack() within 1 in 100. Before those, each stage's own
// records, which need no CPU answer: the grid (its slots a permutation of the particles, each
// cell's in index order, the cells' offsets rising to the count, each entry its particle's
// index and position) and the draw list (the prefix of the drawn particles rises by one exactly
// where a particle's radius and flags say it is drawn, to the draw command's count); a stage
// whose records fail is where the fault lies. Three runs: with the stage clock the device
// takes; with a glFinish after every stage (a check that fails only the first way points at a
// missing barrier or a race, not at the arithmetic); and on the first run's buffers again, for
// the set moved by one ulp (as BM_PerSet1MGpu runs it: a check that fails only on fresh
// buffers points at a read of memory no stage wrote, or wrote too late). Each run reads back
// what each stage received and produced in the order they run, against the CPU's: the
// Attributes buffer after the upload (word for word), the levels' boxes, counts and largest h
// (H_MIN, LEVELS), their grids' corners and sizes and the cell count (LAYOUT: cells along each
// axis within one of the CPU's float mirror, whose pow() may round otherwise), the grid's
// records, the radii, the culling, the draw list; the notes name, per run, the first stage
// apart and its first particle (firstStageApart()). The first particles whose radius is apart
// go to the notes too. A GL context must be current.
// The first failed check of `check` (in the order perSetStageCheck adds them) whose name ends
// in `suffix` ("" for the first run's), as "STAGE: CHECK: FIRST"; empty where all passed.
std::string firstStageApart(const SelfCheck& check, const std::string& suffix);

SelfCheck perSetStageCheck(const core::SceneParticles& particles, const Settings& settings,
                           const glm::dvec3& camera);

}  // namespace twinrender::realtime
