#include "realtime/gl/error.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <string>

namespace twinrender::realtime::gl {

namespace {
const char* errorName(GLenum code) {
    switch (code) {
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        case GL_STACK_UNDERFLOW:
            return "GL_STACK_UNDERFLOW";
        case GL_STACK_OVERFLOW:
            return "GL_STACK_OVERFLOW";
        default:
            return "unknown GL error";
    }
}
}  // namespace

void checkErrors(std::string_view pass) {
    std::string errors;
    // glGetError returns one flag per call until the queue is empty; cap the loop in case a
    // lost context keeps returning an error.
    for (int i = 0; i < 16; ++i) {
        const GLenum code = glGetError();
        if (code == GL_NO_ERROR) break;
        errors += fmt::format("{}{} (0x{:04X})", errors.empty() ? "" : ", ", errorName(code), code);
    }
    if (!errors.empty()) throw Error(fmt::format("OpenGL error in pass '{}': {}", pass, errors));
}

}  // namespace twinrender::realtime::gl
