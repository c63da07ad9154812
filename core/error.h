// Errors that carry their context. Only app/ maps them to exit codes (DESIGN.md):
// InputError -> 4 (bad input or environment), NotComparableError -> 3.
#pragma once

#include <stdexcept>
#include <string>

namespace twinrender::core {

// Bad input or environment: an unreadable or invalid file, an unknown key, no usable GL.
// The message names the file, line or key and says what to do.
class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Two images that cannot be compared (different size or missing channels).
class NotComparableError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace twinrender::core
