#include "realtime/gl/buffer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

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

void Buffer::bindStorage(unsigned binding) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, mHandle.id());
}

void Buffer::bindUniform(unsigned binding) const {
    glBindBufferBase(GL_UNIFORM_BUFFER, binding, mHandle.id());
}

}  // namespace twinrender::realtime::gl
