// An immutable GL buffer (glNamedBufferStorage): uploaded once, read by shaders as a shader
// storage or uniform block.
#pragma once

#include <cstddef>
#include <span>

#include "realtime/gl/handle.h"

namespace twinrender::realtime::gl {

class Buffer {
  public:
    Buffer() = default;
    // Copies `data` into a new buffer (an empty span still gets a small buffer, so that a
    // binding is always valid).
    explicit Buffer(std::span<const std::byte> data);
    template <typename T>
    static Buffer of(std::span<const T> items) {
        return Buffer(std::as_bytes(items));
    }

    // glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding): layout(std430, binding = N).
    void bindStorage(unsigned binding) const;
    // glBindBufferBase(GL_UNIFORM_BUFFER, binding): layout(std140, binding = N).
    void bindUniform(unsigned binding) const;
    std::size_t size() const { return mSize; }
    unsigned id() const { return mHandle.id(); }

  private:
    Handle mHandle;
    std::size_t mSize = 0;
};

}  // namespace twinrender::realtime::gl
