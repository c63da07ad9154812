#include "core/image.h"

#include <algorithm>
#include <fmt/format.h>

#include "core/error.h"

namespace twinrender::core {

Image::Image(int width, int height, std::vector<std::string> channelNames)
    : mWidth(width), mHeight(height), mChannelNames(std::move(channelNames)) {
    if (width < 0 || height < 0)
        throw std::invalid_argument(fmt::format("image size {}x{} is negative", width, height));
    mPixels.assign(static_cast<std::size_t>(width) * height * mChannelNames.size(), 0.0f);
}

int Image::channelIndex(std::string_view name) const {
    auto it = std::find(mChannelNames.begin(), mChannelNames.end(), name);
    return it == mChannelNames.end() ? -1 : static_cast<int>(it - mChannelNames.begin());
}

int Image::requireChannel(std::string_view name) const {
    int c = channelIndex(name);
    if (c < 0) {
        std::string have;
        for (const auto& n : mChannelNames) have += (have.empty() ? "" : ", ") + n;
        throw NotComparableError(
            fmt::format("the image has no channel \"{}\" (it has: {})", name, have));
    }
    return c;
}

void Image::fillChannel(int c, float value) {
    const std::size_t n = pixelCount();
    for (std::size_t p = 0; p < n; ++p) at(p, c) = value;
}

std::vector<float> Image::plane(int c) const {
    std::vector<float> out(pixelCount());
    for (std::size_t p = 0; p < out.size(); ++p) out[p] = at(p, c);
    return out;
}

Image Image::select(std::span<const std::string> names) const {
    Image out(mWidth, mHeight, std::vector<std::string>(names.begin(), names.end()));
    std::vector<int> src;
    for (const auto& n : names) src.push_back(requireChannel(n));
    const std::size_t n = pixelCount();
    for (std::size_t p = 0; p < n; ++p)
        for (std::size_t c = 0; c < src.size(); ++c) out.at(p, static_cast<int>(c)) = at(p, src[c]);
    return out;
}

}  // namespace twinrender::core
