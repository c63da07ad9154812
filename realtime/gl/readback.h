// Textures read back through pixel buffer objects: each read is a GPU command that copies a
// texture into host memory mapped persistently, all of a frame's reads are fenced once, and the
// CPU waits once and reads the mapped memory in place. glReadPixels into client memory waits
// for each read in turn and copies through the driver's own staging.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "realtime/gl/handle.h"
#include "realtime/gl/texture.h"

namespace twinrender::realtime::gl {

class TextureReadback {
  public:
    // Queues the read of `texture` (level 0) into slot `slot` (0, 1, ...): its RGBA values, or
    // with `channels` = 1 its red values alone.
    void read(std::size_t slot, const Texture& texture, int channels = 4);
    // Waits for every read queued since the last wait().
    void wait();
    // Slot `slot`'s pixels (RGBA or red floats, rows from the bottom as GL stores them), valid
    // after wait() until the slot's next read().
    std::span<const float> pixels(std::size_t slot) const;

  private:
    struct Slot {
        Handle buffer;
        const float* mapped = nullptr;
        std::size_t floats = 0;  // the mapping's size
        std::size_t read = 0;    // the last read's
    };
    std::vector<Slot> mSlots;
};

}  // namespace twinrender::realtime::gl
