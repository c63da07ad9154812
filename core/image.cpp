#include "core/image.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#ifdef __linux__
#include <sys/mman.h>
#endif

#include "core/error.h"

namespace twinrender::core {

void adviseHugePages([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes < (std::size_t(4) << 20)) return;
    constexpr std::uintptr_t HUGE_PAGE = std::uintptr_t(1) << 21;
    const auto begin = (reinterpret_cast<std::uintptr_t>(data) + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(HUGE_PAGE - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

Image::Image(int width, int height, std::vector<std::string> channelNames)
    : mWidth(width), mHeight(height), mChannelNames(std::move(channelNames)) {
    if (width < 0 || height < 0)
        throw std::invalid_argument(fmt::format("image size {}x{} is negative", width, height));
    const std::size_t n = static_cast<std::size_t>(width) * height * mChannelNames.size();
    // Allocated untouched first, so that the advice comes before the pages are faulted in.
    reserveHugePages(mPixels, n);
    mPixels.assign(n, 0.0f);
}

Image::Image(int width, int height, std::vector<std::string> channelNames,
             std::vector<float> pixels)
    : mWidth(width),
      mHeight(height),
      mChannelNames(std::move(channelNames)),
      mPixels(std::move(pixels)) {
    if (width < 0 || height < 0 ||
        mPixels.size() != static_cast<std::size_t>(width) * height * mChannelNames.size())
        throw std::invalid_argument(
            fmt::format("{} values do not fill a {}x{} image of {} channels", mPixels.size(), width,
                        height, mChannelNames.size()));
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
