// A linked GLSL program (vertex + fragment) and typed uniform setters. Sources arrive
// composed (version line, #defines, resolved includes); `files` names GLSL source-string
// numbers used in #line directives, so compile logs can be mapped back to files.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "realtime/gl/handle.h"

namespace twinrender::realtime::gl {

struct ShaderSource {
    std::string text;
    std::vector<std::string> files;  // files[i]: the file of "#line N i"
};

class Program {
  public:
    Program() = default;
    // Compiles and links; throws Error with the program name, the driver's log and the
    // source-number-to-file map when either step fails.
    Program(std::string name, const ShaderSource& vertex, const ShaderSource& fragment);

    void use() const;
    const std::string& name() const { return mName; }
    unsigned id() const { return mHandle.id(); }

    // Uniform setters (glProgramUniform*); a name the linker optimised away is ignored.
    void set(std::string_view uniform, float value) const;
    void set(std::string_view uniform, int value) const;
    void set(std::string_view uniform, const glm::vec2& value) const;
    void set(std::string_view uniform, const glm::vec3& value) const;
    void set(std::string_view uniform, const glm::vec4& value) const;
    void set(std::string_view uniform, const glm::ivec2& value) const;
    void set(std::string_view uniform, const glm::mat3& value) const;
    void set(std::string_view uniform, const glm::mat4& value) const;
    void set(std::string_view uniform, std::span<const glm::vec4> values) const;

  private:
    int location(std::string_view uniform) const;

    Handle mHandle;
    std::string mName;
    mutable std::map<std::string, int, std::less<>> mLocations;
};

}  // namespace twinrender::realtime::gl
