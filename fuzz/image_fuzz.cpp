// Fuzz target image: an image given to `compare` (an AOV EXR with any channels, or a PNG;
// the format by its magic number), read and compared with itself and with a copy one step
// brighter: every metric the channels allow.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "compare/metrics.h"
#include "core/image_io.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace twinrender;
    const std::string_view bytes = fuzz::asText(data, size);
    const std::string name = bytes.starts_with("\x89PNG") ? "image.png" : "image.exr";
    const auto file = fuzz::writeScratchFile(name, bytes);
    fuzz::expectCleanOutcome([&] {
        const core::Image image = core::readImage(file);
        compare::computeMetrics(image, image);
        core::Image brighter = image;
        for (float& v : brighter.pixels()) v += 0.25f;
        compare::computeMetrics(image, brighter);
    });
    return 0;
}
