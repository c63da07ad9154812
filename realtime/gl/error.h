// GL failures as exceptions that name the pass (or object) they happened in.
#pragma once

#include <stdexcept>
#include <string_view>

namespace twinrender::realtime::gl {

// A GL call failed, a shader did not compile, a framebuffer is incomplete: a bug or a driver
// limit, not bad input (core::InputError is for that).
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Drains the GL error queue and, on a debug context (ContextOptions::debug), the driver's log
// of error messages; throws Error "OpenGL error in pass 'gbuffer': GL_INVALID_OPERATION
// (0x0502)" (with the driver's messages on a debug context) when either held any.
void checkErrors(std::string_view pass);

}  // namespace twinrender::realtime::gl
