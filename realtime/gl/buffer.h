// An immutable GL buffer (glNamedBufferStorage): uploaded once, read by shaders as a shader
// storage or uniform block.
#pragma once

#include <cstddef>
#include <span>
#include <utility>
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

    // A buffer whose first contents are `data` (at least 16 bytes: zeros after a shorter
    // span), given when it is made; write() and clear() may change it later.
    static Buffer writable(std::span<const std::byte> data);
    template <typename T>
    static Buffer writableOf(std::span<const T> items) {
        return writable(std::as_bytes(items));
    }
    // A buffer of `bytes` zero bytes (at least 16), given when it is made; write() and clear()
    // may change it later.
    static Buffer zeros(std::size_t bytes);
    // A buffer of `bytes` (at least 16) whose contents mean nothing until shaders or write()
    // set them: zeros (cleared on the device, a command ordered before any that uses it), or the
    // poison pattern in poison mode (poison.h), given when it is made.
    static Buffer storage(std::size_t bytes);
    // Fills it with the poison pattern in poison mode (a buffer kept for new contents); else
    // nothing.
    void poison();
    // Every command below that writes the buffer from the client side is ordered after the
    // shader writes issued before it (glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT) first).
    //
    // Sets bytes [offset, offset + data.size()) (a buffer made by writable(), zeros() or
    // storage()).
    void write(std::size_t offset, std::span<const std::byte> data);
    template <typename T>
    void write(std::size_t offset, std::span<const T> items) {
        write(offset, std::as_bytes(items));
    }
    // Sets every byte to 0.
    void clear();
    // Sets bytes [offset, offset + bytes) to 0 (offset and bytes multiples of 4).
    void clearRange(std::size_t offset, std::size_t bytes);
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

// Host memory the CPU writes through a persistent mapping and the GPU copies from into a
// Buffer (glCopyNamedBufferSubData, after glFlushMappedNamedBufferRange of what was written):
// an upload that changes every frame costs one copy by the
// CPU, into memory the GPU reads by DMA, instead of glNamedBufferSubData's copy into the
// driver's own staging and the driver's transfer after it. map() waits until the GPU has
// finished the copies issued from the last mapping (a fence after them).
class StagingBuffer {
  public:
    StagingBuffer() = default;
    ~StagingBuffer();
    StagingBuffer(StagingBuffer&& other) noexcept;
    StagingBuffer& operator=(StagingBuffer&& other) noexcept;

    // `bytes` of mapped memory to write (grown where smaller; contents undefined).
    std::span<std::byte> map(std::size_t bytes);
    // Copies bytes [0, bytes) of the mapping into `destination` from `offset` (a GPU command),
    // then fences it.
    void copyTo(const Buffer& destination, std::size_t offset, std::size_t bytes);

  private:
    void waitForCopies();
    Handle mHandle;
    std::byte* mMapped = nullptr;
    std::size_t mSize = 0;
    void* mFence = nullptr;  // GLsync
};

}  // namespace twinrender::realtime::gl
