// Errors that carry their context. Only app/ maps them to exit codes (docs/design.md):
// InputError (and OutputError) -> 4 (bad input or environment), NotComparableError -> 3.
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

// An output the environment refused: a folder that cannot be written, a full disk. Bad
// environment, so exit 4 as InputError, and never one scene's or one combination's failure
// that a command records and goes past: every later write would fail alike.
class OutputError : public InputError {
  public:
    using InputError::InputError;
};

// Two images that cannot be compared (different size or missing channels).
class NotComparableError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace twinrender::core
