#include "realtime/gl/framebuffer.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>

#include "realtime/gl/error.h"

namespace twinrender::realtime::gl {

namespace {
void deleteFramebuffer(unsigned id) {
    glDeleteFramebuffers(1, &id);
}

const char* statusName(GLenum status) {
    switch (status) {
        case GL_FRAMEBUFFER_UNDEFINED:
            return "GL_FRAMEBUFFER_UNDEFINED";
        case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
            return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
        case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
            return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
        case GL_FRAMEBUFFER_UNSUPPORTED:
            return "GL_FRAMEBUFFER_UNSUPPORTED";
        case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
            return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
        default:
            return "unknown framebuffer status";
    }
}
}  // namespace

Framebuffer::Framebuffer(std::string name, std::vector<Attachment> colour,
                         std::optional<Attachment> depth)
    : mName(std::move(name)), mColourCount(static_cast<int>(colour.size())) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    mHandle = Handle(id, deleteFramebuffer);
    auto size = [&](const Attachment& a) {
        const int w = a.texture->width(a.level), h = a.texture->height(a.level);
        if (mWidth == 0) {
            mWidth = w;
            mHeight = h;
        } else if (w != mWidth || h != mHeight) {
            throw Error(fmt::format("framebuffer '{}': attachments of {}x{} and {}x{}", mName,
                                    mWidth, mHeight, w, h));
        }
    };
    std::vector<GLenum> drawBuffers;
    for (std::size_t i = 0; i < colour.size(); ++i) {
        size(colour[i]);
        glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i),
                                  colour[i].texture->id(), colour[i].level);
        drawBuffers.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    }
    if (depth) {
        size(*depth);
        glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth->texture->id(), depth->level);
    }
    if (drawBuffers.empty())
        glNamedFramebufferDrawBuffer(id, GL_NONE);
    else
        glNamedFramebufferDrawBuffers(id, static_cast<GLsizei>(drawBuffers.size()),
                                      drawBuffers.data());
    const GLenum status = glCheckNamedFramebufferStatus(id, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(fmt::format("framebuffer '{}' is incomplete: {} (0x{:04X})", mName,
                                statusName(status), status));
    checkErrors("framebuffer " + mName);
}

void Framebuffer::bind() const {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, mHandle.id());
    glViewport(0, 0, mWidth, mHeight);
}

void Framebuffer::clearColor(int attachment, const glm::vec4& value) const {
    glClearNamedFramebufferfv(mHandle.id(), GL_COLOR, attachment, &value.x);
}

void Framebuffer::clearDepth(float value) const {
    // Depth writes must be on for the clear to reach the buffer.
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferfv(mHandle.id(), GL_DEPTH, 0, &value);
}

std::vector<float> Framebuffer::read(int attachment, int components) const {
    std::vector<float> pixels(static_cast<std::size_t>(mWidth) * mHeight *
                              static_cast<std::size_t>(std::clamp(components, 1, 4)));
    readInto(attachment, components, pixels);
    return pixels;
}

void Framebuffer::readInto(int attachment, int components, std::span<float> out) const {
    static constexpr GLenum formats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    if (attachment < 0 || attachment >= mColourCount || components < 1 || components > 4)
        throw Error(fmt::format("framebuffer '{}': no colour attachment {} with {} components",
                                mName, attachment, components));
    const std::size_t size = static_cast<std::size_t>(mWidth) * mHeight * components;
    if (out.size() != size)
        throw Error(fmt::format("framebuffer '{}': read into {} floats, needs {}", mName,
                                out.size(), size));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, mHandle.id());
    glNamedFramebufferReadBuffer(mHandle.id(), GL_COLOR_ATTACHMENT0 + attachment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadnPixels(0, 0, mWidth, mHeight, formats[components - 1], GL_FLOAT,
                  static_cast<GLsizei>(size * sizeof(float)), out.data());
    checkErrors("read back " + mName);
}

}  // namespace twinrender::realtime::gl
