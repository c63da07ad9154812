// A buffer viewed as a texture (GL_TEXTURE_BUFFER, read with texelFetch on a samplerBuffer):
// on Mesa's llvmpipe much faster to gather from than a shader storage buffer.
#pragma once

#include <span>

#include "realtime/gl/buffer.h"
#include "realtime/gl/handle.h"

namespace twinrender::realtime::gl {

enum class BufferFormat {
    RGB32F,   // one vec3 texel per 12 bytes
    RGBA32F,  // one vec4 texel per 16 bytes
};

class BufferTexture {
  public:
    BufferTexture() = default;
    BufferTexture(std::span<const std::byte> data, BufferFormat format);
    template <typename T>
    static BufferTexture of(std::span<const T> items, BufferFormat format) {
        return BufferTexture(std::as_bytes(items), format);
    }

    void bind(unsigned unit) const;  // glBindTextureUnit
    std::size_t size() const { return mBuffer.size(); }

  private:
    Buffer mBuffer;
    Handle mTexture;
};

}  // namespace twinrender::realtime::gl
