// One float image type with named channels (pbrt-v4's Image, OpenEXR channel names).
// G-buffer outputs are just more channels ("N.X", "uv.U", "id", ...). Pixels are stored
// interleaved, row-major, row 0 at the top. 8-bit data exists only at file I/O.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace twinrender::core {

// Asks the kernel to back the whole 2 MiB pages inside [data, data + bytes) with huge pages
// (transparent huge pages in "madvise" mode), before they are first touched: an image or a
// metric's plane is tens of MB, and faulting it in 4 KiB at a time costs more than zeroing it
// (on a 1080p PNG pair's compare, 32k page faults and 0.05 s of system time against 8k and
// 0.01 s). Only a hint; nothing for buffers under 4 MiB.
void adviseHugePages(void* data, std::size_t bytes);

// Reserves room for n values in an empty vector, with adviseHugePages.
template <typename T>
void reserveHugePages(std::vector<T>& v, std::size_t n) {
    v.reserve(n);
    adviseHugePages(v.data(), n * sizeof(T));
}

class Image {
  public:
    Image() = default;
    // All values start at zero.
    Image(int width, int height, std::vector<std::string> channelNames);
    // Takes over pixels already filled (interleaved, row-major); their count must be
    // width * height * channelNames.size() (std::invalid_argument otherwise).
    Image(int width, int height, std::vector<std::string> channelNames, std::vector<float> pixels);

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int channelCount() const { return static_cast<int>(mChannelNames.size()); }
    std::size_t pixelCount() const { return static_cast<std::size_t>(mWidth) * mHeight; }
    const std::vector<std::string>& channelNames() const { return mChannelNames; }

    // Index of a channel, or -1 when the image has none of that name.
    int channelIndex(std::string_view name) const;
    bool hasChannel(std::string_view name) const { return channelIndex(name) >= 0; }
    // Index of a channel; throws NotComparableError naming the channel when it is absent.
    int requireChannel(std::string_view name) const;

    float& at(int x, int y, int c) { return mPixels[offset(x, y) + c]; }
    float at(int x, int y, int c) const { return mPixels[offset(x, y) + c]; }
    // Pixel p = y * width + x.
    float& at(std::size_t p, int c) { return mPixels[p * mChannelNames.size() + c]; }
    float at(std::size_t p, int c) const { return mPixels[p * mChannelNames.size() + c]; }

    std::span<float> pixels() { return mPixels; }
    std::span<const float> pixels() const { return mPixels; }

    void fillChannel(int c, float value);
    // A copy of one channel as a dense plane (width * height values).
    std::vector<float> plane(int c) const;
    // A new image holding the named channels, in the order given; absent names throw.
    Image select(std::span<const std::string> names) const;

    bool operator==(const Image& other) const = default;

  private:
    std::size_t offset(int x, int y) const {
        return (static_cast<std::size_t>(y) * mWidth + x) * mChannelNames.size();
    }

    int mWidth = 0;
    int mHeight = 0;
    std::vector<std::string> mChannelNames;
    std::vector<float> mPixels;
};

}  // namespace twinrender::core
