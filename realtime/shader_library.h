// The GLSL files of realtime/shaders/, embedded at build time (cmake/embed_files.cmake), and the
// programs built from them. A shader is composed as: "#version 450 core", the variant's
// #defines, then the file with each `#include "name.glsl"` line replaced by that file (once
// per shader, like #pragma once), with the map of its lines to files (gl::ShaderSource) so
// compile errors name the file and line.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/embedded_file.h"
#include "realtime/gl/program.h"

namespace twinrender::realtime {

using core::EmbeddedFile;

// Every embedded file (defined in the generated embedded_embeddedShaderFiles.cpp).
std::span<const EmbeddedFile> embeddedShaderFiles();

// The text of one embedded file; throws gl::Error naming it when there is none.
std::string_view shaderFile(std::string_view name);

// A file given at run time in place of an embedded one: `#include "<include>"` reads `text`,
// and compile errors name it `shownName` (the user's path).
struct IncludedFile {
    std::string include, shownName, text;
};

// `defines`: "NAME" or "NAME VALUE", each becoming a #define line.
gl::ShaderSource composeShader(std::string_view file, std::span<const std::string> defines,
                               const IncludedFile* user = nullptr);

// Programs by (vertex file, fragment file, defines), compiled on first use, each with the
// conversion test mode's defines first (gl/conversions.h; not part of its name).
class ProgramCache {
  public:
    // `user`: a file the fragment shader includes; programs are kept per its name and text.
    const gl::Program& get(std::string_view vertexFile, std::string_view fragmentFile,
                           const std::vector<std::string>& defines = {},
                           const IncludedFile* user = nullptr);

    // A compute program (a .comp file), compiled on first use.
    const gl::Program& compute(std::string_view file, const std::vector<std::string>& defines = {});

    std::size_t size() const { return mPrograms.size(); }
    // The names of the programs compiled so far (as their errors name them).
    std::vector<std::string> names() const;

    // A program's name: "VERTEX+FRAGMENT -DNAME..." or "COMPUTE -DNAME...".
    static std::string drawName(std::string_view vertexFile, std::string_view fragmentFile,
                                std::span<const std::string> defines);
    static std::string computeName(std::string_view file, std::span<const std::string> defines);

    // Whether the device's GL timer queries see compute dispatches, once per_set_gpu.cpp's
    // probe has run with these programs (the device they were compiled for): kept here, with
    // the device's programs, not in a process-wide table.
    std::optional<bool>& timerQueriesSeeCompute() { return mTimerQueriesSeeCompute; }

  private:
    std::map<std::string, gl::Program, std::less<>> mPrograms;
    std::optional<bool> mTimerQueriesSeeCompute;
};

}  // namespace twinrender::realtime
