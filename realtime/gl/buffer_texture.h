// A buffer viewed as a texture (GL_TEXTURE_BUFFER, read with texelFetch on a samplerBuffer):
// on Mesa's llvmpipe much faster to gather from than a shader storage buffer.
#pragma once

#include <span>

#include "realtime/gl/buffer.h"
#include "realtime/gl/handle.h"

namespace twinrender::realtime::gl {

enum class BufferFormat {
    RGB32F,    // one vec3 texel per 12 bytes
    RGBA32F,   // one vec4 texel per 16 bytes
    RGBA32UI,  // one uvec4 texel per 16 bytes (usamplerBuffer)
    R32UI,     // one uint texel per 4 bytes (usamplerBuffer)
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

// A buffer texture over a buffer kept elsewhere: shaders write the buffer as a storage block
// and later stages read it with texelFetch (after computeBarrier).
class BufferView {
  public:
    // Views the whole of `buffer`, which must outlive the view's use (and be viewed again
    // when it is replaced).
    void view(const Buffer& buffer, BufferFormat format);
    void bind(unsigned unit) const;  // glBindTextureUnit; nothing while nothing is viewed
    bool empty() const { return mTexture.id() == 0; }

  private:
    Handle mTexture;
};

}  // namespace twinrender::realtime::gl
