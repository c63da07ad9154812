#include "realtime/gl/error.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

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

// The messages a debug context logged (ContextOptions::debug; only errors and undefined
// behaviour are enabled), oldest first; none on another context.
std::string loggedMessages() {
    std::string messages;
    GLint logged = 0;
    glGetIntegerv(GL_DEBUG_LOGGED_MESSAGES, &logged);
    if (logged <= 0) return messages;
    GLint maxLength = 0;
    glGetIntegerv(GL_MAX_DEBUG_MESSAGE_LENGTH, &maxLength);
    std::vector<GLenum> types(logged);
    std::vector<GLsizei> lengths(logged);
    std::vector<GLchar> text(static_cast<std::size_t>(logged) * std::max(maxLength, 1));
    const GLuint n =
        glGetDebugMessageLog(static_cast<GLuint>(logged), static_cast<GLsizei>(text.size()),
                             nullptr, types.data(), nullptr, nullptr, lengths.data(), text.data());
    const GLchar* at = text.data();
    for (GLuint i = 0; i < n; ++i) {
        // Lengths count the terminating zero.
        std::string_view message(at, lengths[i] > 0 ? static_cast<std::size_t>(lengths[i] - 1) : 0);
        while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
            message.remove_suffix(1);
        messages +=
            fmt::format("{}{}: {}", messages.empty() ? "" : "; ",
                        types[i] == GL_DEBUG_TYPE_ERROR ? "error" : "undefined behaviour", message);
        at += lengths[i];
    }
    return messages;
}

}  // namespace

void checkErrors(std::string_view pass) {
    const std::string logged = loggedMessages();
    std::string errors;
    // glGetError returns one flag per call until the queue is empty; cap the loop in case a
    // lost context keeps returning an error.
    for (int i = 0; i < 16; ++i) {
        const GLenum code = glGetError();
        if (code == GL_NO_ERROR) break;
        errors += fmt::format("{}{} (0x{:04X})", errors.empty() ? "" : ", ", errorName(code), code);
    }
    if (!logged.empty())
        errors += (errors.empty() ? "the driver's log: " : "; the driver's log: ") + logged;
    if (!errors.empty()) throw Error(fmt::format("OpenGL error in pass '{}': {}", pass, errors));
}

}  // namespace twinrender::realtime::gl
