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

// Drains the GL error queue; throws Error "GL_INVALID_OPERATION (0x0502) in pass 'gbuffer'"
// when it held any error.
void checkErrors(std::string_view pass);

}  // namespace twinrender::realtime::gl
