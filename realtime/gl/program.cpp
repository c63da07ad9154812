#include "realtime/gl/program.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <glm/gtc/type_ptr.hpp>
#include <regex>
#include <sstream>

#include "realtime/gl/error.h"

namespace twinrender::realtime::gl {

namespace {
void deleteProgram(unsigned id) {
    glDeleteProgram(id);
}

// "FILE:LINE" of line `line` of the composed text.
std::string place(const ShaderSource& source, int line) {
    const ShaderSource::Span* span = nullptr;
    for (const auto& s : source.spans)
        if (s.firstLine <= line) span = &s;
    if (!span || span->file >= static_cast<int>(source.files.size()))
        return fmt::format("line {}", line);
    return fmt::format("{}:{}", source.files[span->file], span->fileLine + line - span->firstLine);
}

// The driver's log with each "N:LINE(COLUMN): " (Mesa) or "N(LINE) : " (NVIDIA) prefix
// rewritten as "FILE:LINE:COLUMN: " / "FILE:LINE: ".
std::string namedLog(const std::string& log, const ShaderSource& source) {
    static const std::regex MESA(R"(^\d+:(\d+)\((\d+)\): )");
    static const std::regex NVIDIA(R"(^\d+\((\d+)\) : )");
    std::istringstream lines(log);
    std::string line, out;
    while (std::getline(lines, line)) {
        std::smatch m;
        if (std::regex_search(line, m, MESA))
            line = fmt::format("{}:{}: {}", place(source, std::stoi(m[1])), m[2].str(),
                               m.suffix().str());
        else if (std::regex_search(line, m, NVIDIA))
            line = fmt::format("{}: {}", place(source, std::stoi(m[1])), m.suffix().str());
        out += line + "\n";
    }
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
        throw Error(fmt::format("program '{}': the {} shader does not compile:\n{}", program,
                                stage == GL_VERTEX_SHADER    ? "vertex"
                                : stage == GL_COMPUTE_SHADER ? "compute"
                                                             : "fragment",
                                namedLog(log.c_str(), source)));
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

Program::Program(std::string name, const ShaderSource& compute) : mName(std::move(name)) {
    mHandle = Handle(link(mName, {compile(mName, GL_COMPUTE_SHADER, compute)}), deleteProgram);
    checkErrors("program " + mName);
}

void Program::use() const {
    glUseProgram(mHandle.id());
}

void Program::dispatch(unsigned groups) const {
    use();
    if (groups > 0) glDispatchCompute(groups, 1, 1);
}

void Program::dispatch(unsigned groupsX, unsigned groupsY) const {
    use();
    if (groupsX > 0 && groupsY > 0) glDispatchCompute(groupsX, groupsY, 1);
}

void Program::dispatchIndirect(const Buffer& commands, std::size_t offset) const {
    use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, commands.id());
    glDispatchComputeIndirect(static_cast<GLintptr>(offset));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
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
void Program::set(std::string_view u, unsigned v) const {
    glProgramUniform1ui(id(), location(u), v);
}
void Program::set(std::string_view u, double v) const {
    glProgramUniform1d(id(), location(u), v);
}
void Program::set(std::string_view u, const glm::dvec3& v) const {
    glProgramUniform3dv(id(), location(u), 1, glm::value_ptr(v));
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

int Program::activeStorageBlocks() const {
    GLint count = 0;
    glGetProgramInterfaceiv(mHandle.id(), GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &count);
    return count;
}

std::optional<Program::BufferVariable> Program::bufferVariable(const std::string& name) const {
    const GLuint index = glGetProgramResourceIndex(id(), GL_BUFFER_VARIABLE, name.c_str());
    if (index == GL_INVALID_INDEX) return std::nullopt;
    const GLenum properties[2] = {GL_OFFSET, GL_TOP_LEVEL_ARRAY_STRIDE};
    GLint values[2] = {0, 0};
    glGetProgramResourceiv(id(), GL_BUFFER_VARIABLE, index, 2, properties, 2, nullptr, values);
    return BufferVariable{values[0], values[1]};
}

}  // namespace twinrender::realtime::gl
