// A linked GLSL program (vertex + fragment) and typed uniform setters. Sources arrive
// composed (version line, #defines, resolved includes) with the map of their lines to files,
// so compile logs name the file and line.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "realtime/gl/buffer.h"
#include "realtime/gl/handle.h"

namespace twinrender::realtime::gl {

// A composed shader and where its lines come from: `text` line `firstLine` (1-based) and the
// lines after it, up to the next span, are lines `fileLine`... of files[file]. Drivers name
// lines of the composed text; compile errors are reported by file and line through this map.
struct ShaderSource {
    struct Span {
        int firstLine = 1, file = 0, fileLine = 1;
    };
    std::string text;
    std::vector<std::string> files;
    std::vector<Span> spans;
};

class Program {
  public:
    Program() = default;
    // Compiles and links; throws Error with the program name and the driver's log, its lines
    // named by file and line, when either step fails.
    Program(std::string name, const ShaderSource& vertex, const ShaderSource& fragment);
    // A compute program (GL 4.3): the same, with one compute shader.
    Program(std::string name, const ShaderSource& compute);

    void use() const;
    // use(), then glDispatchCompute(groups, 1, 1) (nothing when groups is 0).
    void dispatch(unsigned groups) const;
    void dispatch(unsigned groupsX, unsigned groupsY) const;  // a 2-D grid of work groups
    // use(), then glDispatchComputeIndirect from `commands` at `offset` bytes (3 uints: the work
    // groups along x, y and z, written by an earlier pass).
    void dispatchIndirect(const Buffer& commands, std::size_t offset) const;
    const std::string& name() const { return mName; }
    unsigned id() const { return mHandle.id(); }

    // Uniform setters (glProgramUniform*); a name the linker optimised away is ignored.
    void set(std::string_view uniform, float value) const;
    void set(std::string_view uniform, int value) const;
    void set(std::string_view uniform, unsigned value) const;
    void set(std::string_view uniform, double value) const;
    void set(std::string_view uniform, const glm::dvec3& value) const;
    void set(std::string_view uniform, const glm::vec2& value) const;
    void set(std::string_view uniform, const glm::vec3& value) const;
    void set(std::string_view uniform, const glm::vec4& value) const;
    void set(std::string_view uniform, const glm::ivec2& value) const;
    void set(std::string_view uniform, const glm::mat3& value) const;
    void set(std::string_view uniform, const glm::mat4& value) const;
    void set(std::string_view uniform, std::span<const glm::vec4> values) const;

    // Where the driver put buffer variable `name` ("walkDispatch", "particles[0].normalU"):
    // its byte offset in its block and, for a member of an array of structs, that array's stride
    // (0 otherwise); std::nullopt where the variable is not active in this program.
    struct BufferVariable {
        long long offset = 0, topLevelStride = 0;
    };
    std::optional<BufferVariable> bufferVariable(const std::string& name) const;
    // The storage blocks the program uses (GL_ACTIVE_RESOURCES of GL_SHADER_STORAGE_BLOCK): what
    // GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS limits. A block declared but not used is not active.
    int activeStorageBlocks() const;

  private:
    int location(std::string_view uniform) const;

    Handle mHandle;
    std::string mName;
    mutable std::map<std::string, int, std::less<>> mLocations;
};

}  // namespace twinrender::realtime::gl
