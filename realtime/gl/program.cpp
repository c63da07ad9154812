#include "realtime/gl/program.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <glm/gtc/type_ptr.hpp>

#include "realtime/gl/error.h"

namespace twinrender::realtime::gl {

namespace {
void deleteProgram(unsigned id) {
    glDeleteProgram(id);
}

std::string fileMap(const ShaderSource& source) {
    std::string out;
    for (std::size_t i = 0; i < source.files.size(); ++i)
        out += fmt::format("{}{} = {}", out.empty() ? "" : ", ", i, source.files[i]);
    return out;
}

GLuint compile(const std::string& program, GLenum stage, const ShaderSource& source) {
    const GLuint shader = glCreateShader(stage);
    const char* text = source.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        throw Error(fmt::format(
            "program '{}': the {} shader does not compile (source numbers: {}):\n{}", program,
            stage == GL_VERTEX_SHADER ? "vertex" : "fragment", fileMap(source), log.c_str()));
    }
    return shader;
}
}  // namespace

namespace {
GLuint link(const std::string& program, std::initializer_list<GLuint> shaders) {
    const GLuint id = glCreateProgram();
    for (GLuint s : shaders) glAttachShader(id, s);
    glLinkProgram(id);
    for (GLuint s : shaders) {
        glDetachShader(id, s);
        glDeleteShader(s);
    }
    GLint ok = GL_FALSE;
    glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint length = 0;
        glGetProgramiv(id, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(id, length, nullptr, log.data());
        glDeleteProgram(id);
        throw Error(fmt::format("program '{}' does not link:\n{}", program, log.c_str()));
    }
    return id;
}
}  // namespace

Program::Program(std::string name, const ShaderSource& vertex, const ShaderSource& fragment)
    : mName(std::move(name)) {
    const GLuint vs = compile(mName, GL_VERTEX_SHADER, vertex);
    GLuint fs = 0;
    try {
        fs = compile(mName, GL_FRAGMENT_SHADER, fragment);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    mHandle = Handle(link(mName, {vs, fs}), deleteProgram);
    checkErrors("program " + mName);
}

void Program::use() const {
    glUseProgram(mHandle.id());
}

int Program::location(std::string_view uniform) const {
    auto it = mLocations.find(uniform);
    if (it == mLocations.end()) {
        const std::string key(uniform);
        it = mLocations.emplace(key, glGetUniformLocation(mHandle.id(), key.c_str())).first;
    }
    return it->second;
}

void Program::set(std::string_view u, float v) const {
    glProgramUniform1f(id(), location(u), v);
}
void Program::set(std::string_view u, int v) const {
    glProgramUniform1i(id(), location(u), v);
}
void Program::set(std::string_view u, const glm::vec2& v) const {
    glProgramUniform2fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::vec3& v) const {
    glProgramUniform3fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::vec4& v) const {
    glProgramUniform4fv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::ivec2& v) const {
    glProgramUniform2iv(id(), location(u), 1, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::mat3& v) const {
    glProgramUniformMatrix3fv(id(), location(u), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view u, const glm::mat4& v) const {
    glProgramUniformMatrix4fv(id(), location(u), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view u, std::span<const glm::vec4> v) const {
    if (!v.empty())
        glProgramUniform4fv(id(), location(u), static_cast<GLsizei>(v.size()),
                            glm::value_ptr(v[0]));
}

}  // namespace twinrender::realtime::gl
