// Display images of the buffers of an AOV image (docs/design.md, "The frame"): what a scene page
// shows for each buffer of both renders, so that a person can see where they differ.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/image.h"

namespace twinrender::report {

// The buffers a scene page can switch between, in its order:
// beauty, normal, uv, depth, id, shadow, ao, emission.
const std::vector<std::string>& bufferNames();

struct BufferVisualSettings {
    float exposure = 1.0f;  // for beauty and emission, as the scene's camera.exposure, > 0
    // Depth range (scene units, 0 < near < far) mapped log-scaled from white (near) to dark
    // grey (far). Both renders of a scene must share it (depthRange of both) so equal
    // depths look equal; {0, 0}: the image's own range.
    std::pair<double, double> depthRange{0.0, 0.0};
};

// The smallest and largest finite positive depth (channel Z, covered pixels) over both
// images; {0, 0} when neither has any.
std::pair<double, double> depthRange(const core::Image& a, const core::Image& b);

// An R, G, B display image in [0, 1] of one buffer of an AOV image (channel names of
// docs/design.md): beauty -> tonemapped R,G,B; normal -> 0.5 + 0.5 n; uv -> (u, v, 0); depth ->
// log-scaled grey; id -> one distinct colour per body (the same in every image); shadow ->
// white lit, grey occluded; ao -> white open, grey closed; emission -> tonemapped. Pixels without
// coverage (A = 0, or Z = inf without A) are a dark slate, except for beauty. Throws
// core::NotComparableError naming the channel when the image lacks one the buffer needs;
// std::invalid_argument for an unknown buffer.
core::Image visualiseBuffer(const core::Image& aov, std::string_view buffer,
                            const BufferVisualSettings& settings = {});

// Writes DIR/<stem>.<buffer>.png for every buffer of bufferNames() whose channels the AOV
// image has and returns buffer -> file name (relative to DIR), ready for
// RendererReport::images. `beautyDisplay` (R, G, B in [0, 1], e.g. the renderer's own PNG
// with bloom) replaces the tonemapped beauty when given.
std::map<std::string, std::string> writeBufferImages(const core::Image& aov,
                                                     const core::Image* beautyDisplay,
                                                     const std::filesystem::path& dir,
                                                     const std::string& stem,
                                                     const BufferVisualSettings& settings = {});

}  // namespace twinrender::report
