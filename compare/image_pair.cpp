#include "compare/image_pair.h"

#include <fmt/format.h>

#include <string>
#include <vector>

#include "core/error.h"

namespace twinrender::compare {

void requireSameSize(std::string_view metric, const core::Image& reference,
                     const core::Image& test) {
    if (reference.width() != test.width() || reference.height() != test.height())
        throw core::NotComparableError(fmt::format(
            "{}: the reference is {}x{} pixels but the test is {}x{}; render both at the same "
            "camera.width and camera.height",
            metric, reference.width(), reference.height(), test.width(), test.height()));
}

const float* rgbPixels(const core::Image& image, core::Image& storage) {
    static const std::vector<std::string> RGB = {"R", "G", "B"};
    if (image.channelNames() == RGB) return image.pixels().data();
    storage = image.select(RGB);
    return storage.pixels().data();
}

}  // namespace twinrender::compare
