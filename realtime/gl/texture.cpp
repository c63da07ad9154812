#include "realtime/gl/texture.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "realtime/gl/error.h"
#include "realtime/gl/poison.h"

namespace twinrender::realtime::gl {

namespace {
void deleteTexture(unsigned id) {
    glDeleteTextures(1, &id);
}

GLenum internalFormat(Format format) {
    switch (format) {
        case Format::RGBA32F:
            return GL_RGBA32F;
        case Format::RGBA16F:
            return GL_RGBA16F;
        case Format::RG32F:
            return GL_RG32F;
        case Format::R32F:
            return GL_R32F;
        case Format::Depth24:
            return GL_DEPTH_COMPONENT24;
        case Format::Depth32F:
            return GL_DEPTH_COMPONENT32F;
    }
    return GL_RGBA32F;
}
}  // namespace

Texture::Texture(int width, int height, Format format, Filter filter, int levels)
    : mWidth(width), mHeight(height), mLevels(levels), mFormat(format) {
    if (width < 1 || height < 1 || levels < 1)
        throw Error(fmt::format("texture size {}x{} with {} levels", width, height, levels));
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    mHandle = Handle(id, deleteTexture);
    glTextureStorage2D(id, levels, internalFormat(format), width, height);
    const GLint minFilter = filter == Filter::Linear
                                ? (levels > 1 ? GL_LINEAR_MIPMAP_NEAREST : GL_LINEAR)
                                : (levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, minFilter);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER,
                        filter == Filter::Linear ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, levels - 1);
    if (poisonMode()) {
        // Depth targets are cleared before use by every pass; colour targets may be read
        // where a pass drew nothing (poison.h).
        const bool depth = format == Format::Depth24 || format == Format::Depth32F;
        const float poison = [] {
            float f;
            const std::uint32_t word = poisonWord();
            static_assert(sizeof(f) == sizeof(word));
            std::memcpy(&f, &word, sizeof(f));
            return f;
        }();
        const float colour[4] = {poison, poison, poison, poison};
        for (int level = 0; level < levels; ++level)
            glClearTexImage(id, level, depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT,
                            depth ? &POISON_DEPTH : colour);
    }
    checkErrors(fmt::format("texture {}x{}", width, height));
}

void Texture::bind(unsigned unit) const {
    glBindTextureUnit(unit, mHandle.id());
}

void Texture::upload(std::span<const float> values) {
    const std::size_t channels = mFormat == Format::R32F ? 1 : mFormat == Format::RGBA32F ? 4 : 0;
    if (channels == 0 || values.size() != static_cast<std::size_t>(mWidth) *
                                              static_cast<std::size_t>(mHeight) * channels)
        throw Error(fmt::format("texture upload: {} values for an {}x{} texture of another format",
                                values.size(), mWidth, mHeight));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(mHandle.id(), 0, 0, 0, mWidth, mHeight, channels == 1 ? GL_RED : GL_RGBA,
                        GL_FLOAT, values.data());
    checkErrors("texture upload");
}

void Texture::bindImageForWriting(unsigned unit) const {
    glBindImageTexture(unit, mHandle.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, internalFormat(mFormat));
}

int Texture::width(int level) const {
    return std::max(1, mWidth >> level);
}
int Texture::height(int level) const {
    return std::max(1, mHeight >> level);
}

}  // namespace twinrender::realtime::gl
