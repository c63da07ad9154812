#include "realtime/gl/buffer_texture.h"

#include <epoxy/gl.h>

namespace twinrender::realtime::gl {

namespace {
void deleteTexture(unsigned id) {
    glDeleteTextures(1, &id);
}

Handle newBufferTexture() {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    return Handle(id, deleteTexture);
}

GLenum internalFormat(BufferFormat format) {
    switch (format) {
        case BufferFormat::RGB32F:
            return GL_RGB32F;
        case BufferFormat::RGBA32F:
            return GL_RGBA32F;
        case BufferFormat::RGBA32UI:
            return GL_RGBA32UI;
        case BufferFormat::R32UI:
            return GL_R32UI;
    }
    return GL_RGBA32F;
}
}  // namespace

BufferTexture::BufferTexture(std::span<const std::byte> data, BufferFormat format)
    : mBuffer(data), mTexture(newBufferTexture()) {
    glTextureBuffer(mTexture.id(), internalFormat(format), mBuffer.id());
}

void BufferTexture::bind(unsigned unit) const {
    glBindTextureUnit(unit, mTexture.id());
}

void BufferView::view(const Buffer& buffer, BufferFormat format) {
    if (empty()) mTexture = newBufferTexture();
    glTextureBuffer(mTexture.id(), internalFormat(format), buffer.id());
}

void BufferView::bind(unsigned unit) const {
    if (!empty()) glBindTextureUnit(unit, mTexture.id());
}

}  // namespace twinrender::realtime::gl
