// A 2-D GL texture with immutable storage, used as a render target and sampled by later
// passes. Always clamped to the edge; Nearest for G-buffer reads with texelFetch, Linear for
// the bloom chain.
#pragma once

#include <span>

#include "realtime/gl/handle.h"

namespace twinrender::realtime::gl {

enum class Format {
    RGBA32F,
    RGBA16F,  // half floats: 10-bit mantissas
    RG32F,
    R32F,
    Depth24,   // 24-bit fixed point: what a default framebuffer offers
    Depth32F,  // float depth: for reversed-Z and the logarithmic buffer
};

enum class Filter { Nearest, Linear };

class Texture {
  public:
    Texture() = default;
    // width, height >= 1; levels >= 1 (a mip chain for the bloom pass).
    Texture(int width, int height, Format format, Filter filter = Filter::Nearest, int levels = 1);

    void bind(unsigned unit) const;  // glBindTextureUnit
    // Level 0 from width x height x channels floats (rows from the bottom): an R32F (one a
    // texel) or RGBA32F (four) texture.
    void upload(std::span<const float> values);
    // glBindImageTexture, level 0, for a compute pass to write (GL_WRITE_ONLY).
    void bindImageForWriting(unsigned unit) const;
    int width(int level = 0) const;
    int height(int level = 0) const;
    int levels() const { return mLevels; }
    Format format() const { return mFormat; }
    bool isDepth() const { return mFormat == Format::Depth24 || mFormat == Format::Depth32F; }
    unsigned id() const { return mHandle.id(); }

  private:
    Handle mHandle;
    int mWidth = 0, mHeight = 0, mLevels = 0;
    Format mFormat = Format::RGBA32F;
};

}  // namespace twinrender::realtime::gl
