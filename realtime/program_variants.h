// Every GLSL program the real-time renderer builds: the shader files with the #defines they are
// compiled with, per settings (what Renderer compiles at set-up, so that no frame compiles) and
// over every setting that changes a program (what `twinrender doctor` and the tests compile).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "realtime/settings.h"
#include "realtime/shader_library.h"

namespace twinrender::realtime {

struct ProgramVariant {
    std::string vertex{}, fragment{};  // a draw program's files
    std::string compute{};             // or a compute program's file
    std::vector<std::string> defines{};
    bool userShader = false;  // the fragment shader includes the user's surface filter

    static ProgramVariant draw(std::string vertex, std::string fragment,
                               std::vector<std::string> defines = {});
    static ProgramVariant computeProgram(std::string file, std::vector<std::string> defines);
    // The user-shader wrapper (user_surface.frag around the user's filter).
    static ProgramVariant userSurface();

    // As ProgramCache names it (the user's filter left out).
    std::string name() const;
    // Compiles it through `programs` (with `user` as the user's filter where userShader);
    // throws gl::Error with the driver's log.
    const gl::Program& build(ProgramCache& programs, const IncludedFile* user = nullptr) const;
};

// The programs a frame with `settings` builds; `emits`: whether anything in the scene emits;
// `emissiveLight`: whether the emissive pass runs (usesEmissiveLight); `atmosphere`: whether a
// body has an atmosphere (the atmosphere pass runs).
std::vector<ProgramVariant> programVariants(const Settings& settings, bool emits,
                                            bool emissiveLight = false, bool atmosphere = false);

// The union of programVariants over every value of every setting that changes a program
// (depth, shadows, shape, normal, radius, droplets, surface method and its separable and
// normals flags, SSSS, emission, bloom, culling, per_set; ambient occlusion and the emissive
// light and the atmosphere's end points beside the defaults), each once, in name order.
std::vector<ProgramVariant> allProgramVariants();

// The surface filter that changes nothing (examples/surface_pass_through.glsl, embedded): the
// user-shader wrapper compiled with it.
IncludedFile passThroughSurfaceFilter();

struct CompileFailure {
    std::string program, log;  // the program's name; the driver's log, named by file and line
};
// Compiles every variant (and checks the per-set programs' layouts, checkPerSetLayouts) and
// returns every failure (not only the first).
std::vector<CompileFailure> compileEach(ProgramCache& programs,
                                        std::span<const ProgramVariant> variants,
                                        const IncludedFile* user = nullptr);

}  // namespace twinrender::realtime
