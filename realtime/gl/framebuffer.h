// A framebuffer object over textures the caller owns (they must outlive it).
#pragma once

#include <glm/vec4.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "realtime/gl/handle.h"
#include "realtime/gl/texture.h"

namespace twinrender::realtime::gl {

struct Attachment {
    const Texture* texture = nullptr;
    int level = 0;  // mip level
};

class Framebuffer {
  public:
    Framebuffer() = default;
    // Throws Error naming the framebuffer when it is incomplete or the attachments differ in size.
    Framebuffer(std::string name, std::vector<Attachment> colour,
                std::optional<Attachment> depth = std::nullopt);

    // Binds it for drawing, enables all colour attachments and sets the viewport to its size.
    void bind() const;
    void clearColor(int attachment, const glm::vec4& value) const;
    void clearDepth(float value) const;
    // Colour attachment `attachment` as floats, `components` (1..4) per pixel, OpenGL order:
    // the bottom row first.
    std::vector<float> read(int attachment, int components) const;
    // The same into `out` (width * height * components floats), which the caller may keep
    // between frames: a fresh buffer of a full-screen float image costs its page faults again.
    void readInto(int attachment, int components, std::span<float> out) const;

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    const std::string& name() const { return mName; }

  private:
    Handle mHandle;
    std::string mName;
    int mWidth = 0, mHeight = 0;
    int mColourCount = 0;
};

}  // namespace twinrender::realtime::gl
