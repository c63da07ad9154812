#include "realtime/gl/buffer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

#include "realtime/gl/poison.h"

namespace twinrender::realtime::gl {

namespace {
void deleteBuffer(unsigned id) {
    glDeleteBuffers(1, &id);
}
}  // namespace

Buffer::Buffer(std::span<const std::byte> data) : mSize(data.size()) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    mHandle = Handle(id, deleteBuffer);
    if (data.empty()) {
        const std::vector<std::byte> zeros(16);
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(zeros.size()), zeros.data(), 0);
    } else {
        glNamedBufferStorage(id, static_cast<GLsizeiptr>(data.size()), data.data(), 0);
    }
}

Buffer Buffer::zeros(std::size_t bytes) {
    Buffer b;
    b.mSize = std::max<std::size_t>(bytes, 16);
    GLuint id = 0;
    glCreateBuffers(1, &id);
    b.mHandle = Handle(id, deleteBuffer);
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(b.mSize), nullptr, GL_DYNAMIC_STORAGE_BIT);
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
    glClearNamedBufferData(mHandle.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &POISON_WORD);
}

void Buffer::write(std::size_t offset, std::span<const std::byte> data) {
    if (!data.empty())
        glNamedBufferSubData(mHandle.id(), static_cast<GLintptr>(offset),
                             static_cast<GLsizeiptr>(data.size()), data.data());
}

void Buffer::clear() {
    glClearNamedBufferData(mHandle.id(), GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, nullptr);
}

void Buffer::read(std::size_t offset, std::span<std::byte> out) const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!out.empty())
        glGetNamedBufferSubData(mHandle.id(), static_cast<GLintptr>(offset),
                                static_cast<GLsizeiptr>(out.size()), out.data());
}

void Buffer::bindStorage(unsigned binding) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, mHandle.id());
}

void Buffer::bindUniform(unsigned binding) const {
    glBindBufferBase(GL_UNIFORM_BUFFER, binding, mHandle.id());
}

}  // namespace twinrender::realtime::gl
