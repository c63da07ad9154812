#include "realtime/gl/buffer_texture.h"

#include <epoxy/gl.h>

namespace twinrender::realtime::gl {

namespace {
void deleteTexture(unsigned id) {
    glDeleteTextures(1, &id);
}
}  // namespace

BufferTexture::BufferTexture(std::span<const std::byte> data, BufferFormat format) : mBuffer(data) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    mTexture = Handle(id, deleteTexture);
    glTextureBuffer(id, format == BufferFormat::RGB32F ? GL_RGB32F : GL_RGBA32F, mBuffer.id());
}

void BufferTexture::bind(unsigned unit) const {
    glBindTextureUnit(unit, mTexture.id());
}

}  // namespace twinrender::realtime::gl
