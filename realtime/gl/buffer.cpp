#include "realtime/gl/buffer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gl/poison.h"

namespace twinrender::realtime::gl {

namespace {
void deleteBuffer(unsigned id) {
    glDeleteBuffers(1, &id);
}

// Poison mode: the bytes of poison after every buffer's own. A shader that reads past the end
// of a buffer reads zero on llvmpipe (its accesses are bounds-checked) and, on a GPU without
// robust access, whatever lies after it; with the tail it reads poisonWord(), on any driver.
// Shaders here never take a buffer's length(), so the tail changes nothing else.
std::size_t poisonTail() {
    return poisonMode() ? 4096 : 0;
}

// Where the tail starts: the poison pattern is written in whole words.
std::size_t wordsEnd(std::size_t bytes) {
    return (bytes + 3) / 4 * 4;
}

// Before a command that writes a buffer from the client side (glNamedBufferSubData,
// glClearNamedBufferSubData, glCopyNamedBufferSubData): shader writes issued before it must
// land first, which GL orders only through this barrier.
void barrierBeforeUpdate() {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

void fillPoison(unsigned id, std::size_t offset, std::size_t bytes) {
    const std::uint32_t word = poisonWord();
    if (bytes > 0)
        glClearNamedBufferSubData(id, GL_R32UI, static_cast<GLintptr>(offset),
                                  static_cast<GLsizeiptr>(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT,
                                  &word);
}

// What a new buffer holds when it is made.
enum class Contents {
    Given,   // the data passed
    Zeros,   // zero bytes
    Shaders  // nothing yet: the shaders that use it write what they read (zeros; poison mode's
             // pattern)
};

// A new buffer of `bytes` (and the poison tail) whose first contents glNamedBufferStorage
// gives it, or (Contents::Shaders outside poison mode) a clear ordered before any command that
// uses it: no command writes it before it exists with its contents.
Handle makeBuffer(std::size_t bytes, const void* data, Contents contents, unsigned flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Handle handle(id, deleteBuffer);
    const std::size_t tail = poisonTail();
    if (tail == 0 && contents == Contents::Shaders) {
        // Large buffers (the per-set stages' tens of MB at 1M particles): zeroed on the device
        // instead of copying zeros from the client.
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), nullptr, flags);
        glClearNamedBufferSubData(id, GL_R8UI, 0, static_cast<GLsizeiptr>(bytes), GL_RED_INTEGER,
                                  GL_UNSIGNED_BYTE, nullptr);
        return handle;
    }
    if (tail == 0 && contents == Contents::Given) {
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
        return handle;
    }
    // Zeros, or poison mode: the whole first contents from the client (the pattern where
    // shaders are to write, and after the buffer's own words).
    std::vector<std::uint32_t> words((wordsEnd(bytes) + tail) / 4,
                                     contents == Contents::Shaders ? poisonWord() : 0u);
    if (contents == Contents::Given) std::memcpy(words.data(), data, bytes);
    for (std::size_t w = wordsEnd(bytes) / 4; w < words.size(); ++w) words[w] = poisonWord();
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(words.size() * 4), words.data(), flags);
    return handle;
}
}  // namespace

Buffer::Buffer(std::span<const std::byte> data) : mSize(data.size()) {
    if (data.empty()) {
        mSize = 16;
        mHandle = makeBuffer(mSize, nullptr, Contents::Zeros, 0);
    } else {
        mHandle = makeBuffer(data.size(), data.data(), Contents::Given, 0);
    }
}

Buffer Buffer::writable(std::span<const std::byte> data) {
    Buffer b;
    b.mSize = std::max<std::size_t>(data.size(), 16);
    b.mHandle = data.size() >= 16
                    ? makeBuffer(b.mSize, data.data(), Contents::Given, GL_DYNAMIC_STORAGE_BIT)
                    : makeBuffer(b.mSize, nullptr, Contents::Zeros, GL_DYNAMIC_STORAGE_BIT);
    if (!data.empty() && data.size() < 16) b.write(0, data);
    return b;
}

Buffer Buffer::zeros(std::size_t bytes) {
    Buffer b;
    b.mSize = std::max<std::size_t>(bytes, 16);
    b.mHandle = makeBuffer(b.mSize, nullptr, Contents::Zeros, GL_DYNAMIC_STORAGE_BIT);
    return b;
}

Buffer Buffer::storage(std::size_t bytes) {
    Buffer b;
    b.mSize = std::max<std::size_t>(bytes, 16);
    b.mHandle = makeBuffer(b.mSize, nullptr, Contents::Shaders, GL_DYNAMIC_STORAGE_BIT);
    return b;
}

void Buffer::poison() {
    if (!poisonMode() || !mHandle) return;
    barrierBeforeUpdate();
    fillPoison(mHandle.id(), 0, wordsEnd(mSize) + poisonTail());
}

void Buffer::write(std::size_t offset, std::span<const std::byte> data) {
    if (data.empty()) return;
    barrierBeforeUpdate();
    glNamedBufferSubData(mHandle.id(), static_cast<GLintptr>(offset),
                         static_cast<GLsizeiptr>(data.size()), data.data());
}

void Buffer::clear() {
    barrierBeforeUpdate();
    glClearNamedBufferSubData(mHandle.id(), GL_R8UI, 0, static_cast<GLintptr>(mSize),
                              GL_RED_INTEGER, GL_UNSIGNED_BYTE, nullptr);
}

void Buffer::clearRange(std::size_t offset, std::size_t bytes) {
    barrierBeforeUpdate();
    glClearNamedBufferSubData(mHandle.id(), GL_R32UI, static_cast<GLintptr>(offset),
                              static_cast<GLsizeiptr>(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT,
                              nullptr);
}

void Buffer::read(std::size_t offset, std::span<std::byte> out) const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!out.empty())
        glGetNamedBufferSubData(mHandle.id(), static_cast<GLintptr>(offset),
                                static_cast<GLsizeiptr>(out.size()), out.data());
}

bool Buffer::overrun() const {
    const std::size_t tail = poisonTail();
    if (tail == 0 || !mHandle) return false;
    std::vector<std::uint32_t> words(tail / 4);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(mHandle.id(), static_cast<GLintptr>(wordsEnd(mSize)),
                            static_cast<GLsizeiptr>(tail), words.data());
    const std::uint32_t word = poisonWord();
    return std::ranges::any_of(words, [&](std::uint32_t w) { return w != word; });
}

void Buffer::bindStorage(unsigned binding) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, mHandle.id());
}

void Buffer::bindUniform(unsigned binding) const {
    glBindBufferBase(GL_UNIFORM_BUFFER, binding, mHandle.id());
}

StagingBuffer::~StagingBuffer() {
    if (mFence) glDeleteSync(static_cast<GLsync>(mFence));
}

StagingBuffer::StagingBuffer(StagingBuffer&& other) noexcept
    : mHandle(std::move(other.mHandle)),
      mMapped(std::exchange(other.mMapped, nullptr)),
      mSize(std::exchange(other.mSize, 0)),
      mFence(std::exchange(other.mFence, nullptr)) {}

StagingBuffer& StagingBuffer::operator=(StagingBuffer&& other) noexcept {
    if (this != &other) {
        if (mFence) glDeleteSync(static_cast<GLsync>(mFence));
        mHandle = std::move(other.mHandle);
        mMapped = std::exchange(other.mMapped, nullptr);
        mSize = std::exchange(other.mSize, 0);
        mFence = std::exchange(other.mFence, nullptr);
    }
    return *this;
}

void StagingBuffer::waitForCopies() {
    if (!mFence) return;
    waitAndDelete(mFence);
    mFence = nullptr;
}

std::span<std::byte> StagingBuffer::map(std::size_t bytes) {
    waitForCopies();
    if (bytes > mSize || !mHandle) {
        mHandle = Handle();
        mMapped = nullptr;
        mSize = std::max<std::size_t>(bytes, 16);
        GLuint id = 0;
        glCreateBuffers(1, &id);
        mHandle = Handle(id, deleteBuffer);
        // Not coherent: copyTo() flushes what the client wrote (glFlushMappedNamedBufferRange)
        // before the copy, the one order the spec states for client writes through a mapping.
        const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT;
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(mSize), nullptr, flags);
        mMapped = static_cast<std::byte*>(glMapNamedBufferRange(
            id, 0, static_cast<GLsizeiptr>(mSize), flags | GL_MAP_FLUSH_EXPLICIT_BIT));
        if (!mMapped) throw Error("could not map a staging buffer for writing");
    }
    return {mMapped, bytes};
}

void StagingBuffer::copyTo(const Buffer& destination, std::size_t offset, std::size_t bytes) {
    if (bytes == 0) return;
    glFlushMappedNamedBufferRange(mHandle.id(), 0, static_cast<GLsizeiptr>(bytes));
    barrierBeforeUpdate();  // the destination's last contents may have come from shaders
    glCopyNamedBufferSubData(mHandle.id(), destination.id(), 0, static_cast<GLintptr>(offset),
                             static_cast<GLsizeiptr>(bytes));
    if (mFence) glDeleteSync(static_cast<GLsync>(mFence));
    mFence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

}  // namespace twinrender::realtime::gl
