// An immutable GL buffer (glNamedBufferStorage): uploaded once, read by shaders as a shader
// storage or uniform block.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

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

    // A buffer of `bytes` zero bytes (at least 16) that shaders fill; write() and clear() may
    // change it later.
    static Buffer zeros(std::size_t bytes);
    // A buffer of `bytes` (at least 16) whose contents mean nothing until shaders or write()
    // set them: zeros, or the poison pattern in poison mode (poison.h).
    static Buffer storage(std::size_t bytes);
    // Fills it with the poison pattern in poison mode (a buffer kept for new contents); else
    // nothing.
    void poison();
    // Sets bytes [offset, offset + data.size()) (a buffer made by zeros() only).
    void write(std::size_t offset, std::span<const std::byte> data);
    template <typename T>
    void write(std::size_t offset, std::span<const T> items) {
        write(offset, std::as_bytes(items));
    }
    // Sets every byte to 0.
    void clear();
    // Copies bytes [offset, offset + out.size()) back (waits for the writes before it).
    void read(std::size_t offset, std::span<std::byte> out) const;
    template <typename T>
    std::vector<T> read(std::size_t first, std::size_t count) const {
        std::vector<T> out(count);
        read(first * sizeof(T), std::as_writable_bytes(std::span<T>(out)));
        return out;
    }

    // Poison mode: whether a shader wrote past the buffer's end, into the poison tail that
    // follows it there (buffer.cpp); a GPU would have written into whatever lies after it.
    // Always false outside poison mode.
    bool overrun() const;

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
