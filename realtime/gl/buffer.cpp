#include "realtime/gl/buffer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdint>
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
// robust access, whatever lies after it; with the tail it reads POISON_WORD, on any driver.
// Shaders here never take a buffer's length(), so the tail changes nothing else.
std::size_t poisonTail() {
    return poisonMode() ? 4096 : 0;
}

// Where the tail starts: the poison pattern is written in whole words.
std::size_t wordsEnd(std::size_t bytes) {
    return (bytes + 3) / 4 * 4;
}

void fillPoison(unsigned id, std::size_t offset, std::size_t bytes) {
    if (bytes > 0)
        glClearNamedBufferSubData(id, GL_R32UI, static_cast<GLintptr>(offset),
                                  static_cast<GLsizeiptr>(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT,
                                  &POISON_WORD);
}

// A new buffer of `bytes` (and the poison tail), its contents `data` where given.
Handle makeBuffer(std::size_t bytes, const void* data, unsigned flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Handle handle(id, deleteBuffer);
    const std::size_t tail = poisonTail();
    if (tail == 0) {
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
        return handle;
    }
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(wordsEnd(bytes) + tail), nullptr,
                         flags | GL_DYNAMIC_STORAGE_BIT);
    if (data) glNamedBufferSubData(id, 0, static_cast<GLsizeiptr>(bytes), data);
    fillPoison(id, wordsEnd(bytes), tail);
    return handle;
}
}  // namespace

Buffer::Buffer(std::span<const std::byte> data) : mSize(data.size()) {
    if (data.empty()) {
        const std::vector<std::byte> zeros(16);
        mHandle = makeBuffer(zeros.size(), zeros.data(), 0);
    } else {
        mHandle = makeBuffer(data.size(), data.data(), 0);
    }
}

Buffer Buffer::zeros(std::size_t bytes) {
    Buffer b;
    b.mSize = std::max<std::size_t>(bytes, 16);
    b.mHandle = makeBuffer(b.mSize, nullptr, GL_DYNAMIC_STORAGE_BIT);
    b.clear();
    return b;
}

Buffer Buffer::storage(std::size_t bytes) {
    Buffer b = zeros(bytes);
    b.poison();
    return b;
}

void Buffer::poison() {
    if (!poisonMode() || !mHandle) return;
    fillPoison(mHandle.id(), 0, wordsEnd(mSize) + poisonTail());
}

void Buffer::write(std::size_t offset, std::span<const std::byte> data) {
    if (!data.empty())
        glNamedBufferSubData(mHandle.id(), static_cast<GLintptr>(offset),
                             static_cast<GLsizeiptr>(data.size()), data.data());
}

void Buffer::clear() {
    glClearNamedBufferSubData(mHandle.id(), GL_R8UI, 0, static_cast<GLintptr>(mSize),
                              GL_RED_INTEGER, GL_UNSIGNED_BYTE, nullptr);
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
    return std::ranges::any_of(words, [](std::uint32_t w) { return w != POISON_WORD; });
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
        const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(mSize), nullptr, flags);
        mMapped = static_cast<std::byte*>(
            glMapNamedBufferRange(id, 0, static_cast<GLsizeiptr>(mSize), flags));
        if (!mMapped) throw Error("could not map a staging buffer for writing");
    }
    return {mMapped, bytes};
}

void StagingBuffer::copyTo(const Buffer& destination, std::size_t offset, std::size_t bytes) {
    if (bytes == 0) return;
    glCopyNamedBufferSubData(mHandle.id(), destination.id(), 0, static_cast<GLintptr>(offset),
                             static_cast<GLsizeiptr>(bytes));
    if (mFence) glDeleteSync(static_cast<GLsync>(mFence));
    mFence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

}  // namespace twinrender::realtime::gl
