// What a renderer returns (core/renderer.h): the AOV image of docs/design.md, the image a person
// looks at, and the facts the JSON beside them records (settings, device, counters, stage
// timings).
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/frame_part.h"
#include "core/image.h"

namespace twinrender::core {

// The AOV channels in file order, and their background values.
namespace aov {
inline const std::vector<std::string>& channelNames() {
    static const std::vector<std::string> names = {"R",
                                                   "G",
                                                   "B",
                                                   "A",
                                                   "Z",
                                                   "N.X",
                                                   "N.Y",
                                                   "N.Z",
                                                   "uv.U",
                                                   "uv.V",
                                                   "id",
                                                   "emission.R",
                                                   "emission.G",
                                                   "emission.B",
                                                   "shadow",
                                                   "ao",
                                                   "irradiance.R",
                                                   "irradiance.G",
                                                   "irradiance.B",
                                                   "inscatter.R",
                                                   "inscatter.G",
                                                   "inscatter.B"};
    return names;
}
// An image with every AOV channel set to its background (Z = +inf, id = -1, others 0).
Image makeImage(int width, int height);
}  // namespace aov

struct Frame {
    Image image;  // the AOV image
    // What the PNG shows: sRGB R, G, B in [0, 1], top row first; core's tonemapper, after bloom
    // when the renderer does bloom.
    Image display;
    std::string renderer;                    // "raymarch" or "realtime"
    std::string device;                      // GL_RENDERER, or the CPU model and thread count
    nlohmann::json settings;                 // every setting used, by dotted key
    std::map<std::string, double> counters;  // e.g. "unbracketed_rays"
    // "total" (the render, without process start and file I/O) and one entry per stage.
    std::map<std::string, double> timingsMs;
    std::size_t particleCount = 0;
    // With RenderInput::exactSurface, the images of the error split (linear R, G, B): the
    // renderer's shading of its own surface with the reference's light ("surface": what its
    // surface costs), of the reference's surface with its own light ("lighting": what its
    // shadow and occlusion cost), and of the reference's surface with the reference's light
    // ("shading": what its shading alone costs, rounding).
    std::map<std::string, Image> split;
    // Set when the renderer drew one part of the frame (RenderInput::part): which, and what
    // joining the parts needs (core/part_join.h). The images then hold the part's rows alone.
    std::optional<PartRecord> part;
};

// The tonemapped sRGB beauty (R, G, B in [0, 1]) a person looks at.
Image tonemappedBeauty(const Image& aovImage, float exposure);

// Writes DIR/R.exr (all AOV channels, linear), DIR/R.png (the display image) and DIR/R.json,
// R the frame's renderer; each file atomically. `extra` is merged into the JSON (scene name,
// resolution, ...). A part of a frame (core/frame_part.h) writes no R.png, and its record as
// R.json's "tile".
void writeFrame(const Frame& frame, const std::filesystem::path& dir, const nlohmann::json& extra);

// Reads what writeFrame wrote for `renderer` in DIR (the display image left empty): the AOV
// image, and from the JSON the device,
// settings, particle count, counters, timings and a part's record. `json`, when given, receives the
// whole JSON. Throws InputError naming the file when one is missing or unreadable, or the JSON is
// not an object or holds a damaged "tile".
Frame readFrame(const std::filesystem::path& dir, const std::string& renderer,
                nlohmann::json* json = nullptr);

}  // namespace twinrender::core
