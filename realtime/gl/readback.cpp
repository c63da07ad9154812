#include "realtime/gl/readback.h"

#include <epoxy/gl.h>

#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"

namespace twinrender::realtime::gl {

namespace {
void deleteBuffer(unsigned id) {
    glDeleteBuffers(1, &id);
}
}  // namespace

void TextureReadback::read(std::size_t slot, const Texture& texture, int channels) {
    if (slot >= mSlots.size()) mSlots.resize(slot + 1);
    Slot& s = mSlots[slot];
    const std::size_t floats =
        static_cast<std::size_t>(texture.width()) * texture.height() * (channels == 1 ? 1 : 4);
    if (floats > s.floats || !s.buffer) {
        GLuint id = 0;
        glCreateBuffers(1, &id);
        s.buffer = Handle(id, deleteBuffer);
        const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        const auto bytes = static_cast<GLsizeiptr>(floats * sizeof(float));
        glNamedBufferStorage(id, bytes, nullptr, flags | GL_CLIENT_STORAGE_BIT);
        s.mapped = static_cast<const float*>(glMapNamedBufferRange(id, 0, bytes, flags));
        if (!s.mapped) throw Error("could not map a pixel buffer for reading");
        s.floats = floats;
    }
    s.read = floats;
    // A texture a shader wrote by image store (the gradient gather's) reaches glGetTextureImage
    // only through this barrier; a render target's writes need none.
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, s.buffer.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture.id(), 0, channels == 1 ? GL_RED : GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(floats * sizeof(float)), nullptr);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

void TextureReadback::wait() {
    // The copies' writes into the mapped memory are seen by the CPU once the fence signals.
    glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    waitAndDelete(glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0));
    checkErrors("read back textures");
}

std::span<const float> TextureReadback::pixels(std::size_t slot) const {
    const Slot& s = mSlots.at(slot);
    return {s.mapped, s.read};
}

}  // namespace twinrender::realtime::gl
