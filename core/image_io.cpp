#include "core/image_io.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <fstream>

#include "core/error.h"

namespace twinrender::core {
namespace fs = std::filesystem;
namespace OIIO = OIIO_NAMESPACE;

namespace {

// The largest image read: the camera's largest width and height (scene.h), and at most 2^28
// values (1 GiB of floats), so that a damaged header cannot ask for more memory than any
// image the suite writes.
constexpr int MOST_IMAGE_SIDE = 16384;
constexpr double MOST_IMAGE_VALUES = 268435456.0;

// OpenEXR allocates what a header attribute's size field says before it reads the value, so a
// few flipped bytes of a header ask for gigabytes: check every attribute's size against the
// bytes the file has, before the library opens it. Header layout (OpenEXR's file layout
// document): magic 20000630, version (bit 12: several parts), then per part the attributes
// (name\0 type\0 int32 size, value) ended by an empty name, the parts ended by an empty
// header.
void checkExrHeader(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    const auto size = static_cast<std::int64_t>(fs::file_size(path));
    auto corrupt = [&](const std::string& what) {
        return InputError(fmt::format("{}: not a valid OpenEXR file: {}; the file is damaged",
                                      path.string(), what));
    };
    unsigned char head[8] = {};
    if (!in.read(reinterpret_cast<char*>(head), 8)) return;  // too short: OpenEXR says so
    if (!(head[0] == 0x76 && head[1] == 0x2f && head[2] == 0x31 && head[3] == 0x01)) return;
    const bool multipart = (head[5] & 0x10) != 0;
    auto readName = [&]() {
        std::string name;
        for (char c; in.get(c) && c != '\0';)
            if (name.size() < 256) name += c;
        return name;
    };
    auto int32At = [](const std::string& v, std::size_t at) {
        return std::int32_t(std::uint32_t(std::uint8_t(v[at])) |
                            std::uint32_t(std::uint8_t(v[at + 1])) << 8 |
                            std::uint32_t(std::uint8_t(v[at + 2])) << 16 |
                            std::uint32_t(std::uint8_t(v[at + 3])) << 24);
    };
    for (int part = 0;; ++part) {
        int attributes = 0;
        // The data window's size and the channel count: OpenEXR sizes its buffers by them.
        double width = 1.0, height = 1.0, channels = 1.0;
        for (;; ++attributes) {
            const std::string name = readName();
            if (!in) throw corrupt(fmt::format("the header of part {} ends early", part));
            if (name.empty()) break;
            const std::string type = readName();
            unsigned char b[4] = {};
            in.read(reinterpret_cast<char*>(b), 4);
            const std::int64_t bytes =
                std::int32_t(std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                             std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24);
            const std::int64_t at = in.tellg();
            if (!in || bytes < 0 || bytes > size - at)
                throw corrupt(
                    fmt::format("header attribute '{}' ({}) claims {} bytes at byte {} "
                                "of {}",
                                name, type, bytes, at, size));
            if ((name == "dataWindow" && bytes == 16) || (name == "channels" && type == "chlist")) {
                std::string value(static_cast<std::size_t>(bytes), '\0');
                in.read(value.data(), bytes);
                if (name == "dataWindow") {
                    width = double(int32At(value, 8)) - int32At(value, 0) + 1.0;
                    height = double(int32At(value, 12)) - int32At(value, 4) + 1.0;
                } else {
                    // Entries: name\0 and 16 bytes (type, linear, reserved, sampling).
                    channels = 0.0;
                    for (std::size_t at = 0; at < value.size() && value[at] != '\0';) {
                        const std::size_t end = value.find('\0', at);
                        if (end == std::string::npos) break;
                        ++channels;
                        at = end + 17;
                    }
                }
            } else {
                in.seekg(bytes, std::ios::cur);
            }
        }
        if (width < 1.0 || height < 1.0 || width > MOST_IMAGE_SIDE || height > MOST_IMAGE_SIDE ||
            width * height * std::max(channels, 1.0) > MOST_IMAGE_VALUES)
            throw corrupt(
                fmt::format("part {} has a data window of {} x {} pixels with {} "
                            "channels; images up to {} pixels a side and {:g} values "
                            "in all are read",
                            part, width, height, channels, MOST_IMAGE_SIDE, MOST_IMAGE_VALUES));
        if (!multipart || attributes == 0) return;
    }
}

}  // namespace

Image readImage(const fs::path& path) {
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) checkExrHeader(path);
    auto in = OIIO::ImageInput::open(path.string());
    if (!in)
        throw InputError(fmt::format("{}: cannot read the image ({}); check the path and format",
                                     path.string(), OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 1 || spec.height < 1 || spec.width > MOST_IMAGE_SIDE ||
        spec.height > MOST_IMAGE_SIDE || spec.depth > 1 || spec.nchannels < 1 ||
        double(spec.width) * spec.height * spec.nchannels > MOST_IMAGE_VALUES)
        throw InputError(fmt::format(
            "{}: the image is {} x {} x {} pixels with {} channels; flat images up to {} pixels "
            "a side and {:g} values in all are read (the header may be damaged)",
            path.string(), spec.width, spec.height, spec.depth, spec.nchannels, MOST_IMAGE_SIDE,
            MOST_IMAGE_VALUES));
    std::vector<std::string> names;
    const bool isFloat = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                         spec.format.basetype == OIIO::TypeDesc::HALF;
    for (int c = 0; c < spec.nchannels; ++c) {
        std::string name = c < static_cast<int>(spec.channelnames.size())
                               ? spec.channelnames[c]
                               : fmt::format("channel{}", c);
        names.push_back(std::move(name));
    }
    if (!isFloat) {
        // Plain images: name the channels by position, whatever the file says.
        static const char* kRgba[] = {"R", "G", "B", "A"};
        if (spec.nchannels == 1)
            names = {"Y"};
        else
            for (int c = 0; c < spec.nchannels && c < 4; ++c) names[c] = kRgba[c];
    }
    Image image(spec.width, spec.height, names);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels().data()))
        throw InputError(
            fmt::format("{}: the image data cannot be read ({}); the file may be "
                        "truncated",
                        path.string(), in->geterror()));
    // A grey image stands for R = G = B.
    if (!isFloat && spec.nchannels <= 2) {
        Image rgb(spec.width, spec.height, {"R", "G", "B"});
        for (std::size_t p = 0; p < image.pixelCount(); ++p)
            for (int c = 0; c < 3; ++c) rgb.at(p, c) = image.at(p, 0);
        return rgb;
    }
    return image;
}

void writeFileAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    static std::atomic<unsigned> counter{0};
    if (path.has_parent_path()) fs::create_directories(path.parent_path());
    fs::path tmp = path;
    tmp.replace_filename(fmt::format(".{}.tmp{}-{}{}", path.stem().string(), getpid(), counter++,
                                     path.extension().string()));
    try {
        write(tmp);
        fs::rename(tmp, path);
    } catch (...) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
}

void writeTextFile(const fs::path& path, std::string_view text) {
    writeFileAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        if (!out) throw InputError(fmt::format("{}: cannot write the file", path.string()));
    });
}

namespace {

void writeWithOiio(const fs::path& path, const OIIO::ImageSpec& spec, const void* data,
                   OIIO::TypeDesc dataType) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out || !out->open(path.string(), spec) || !out->write_image(dataType, data) ||
        !out->close())
        throw InputError(
            fmt::format("{}: cannot write the image ({}); check that the folder is "
                        "writable",
                        path.string(), out ? out->geterror() : OIIO::geterror()));
}

}  // namespace

void writeImage(const Image& image, const fs::path& path) {
    const std::string ext = path.extension().string();
    writeFileAtomically(path, [&](const fs::path& tmp) {
        if (ext == ".exr") {
            OIIO::ImageSpec spec(image.width(), image.height(), image.channelCount(),
                                 OIIO::TypeDesc::FLOAT);
            spec.channelnames = image.channelNames();
            spec.alpha_channel = image.channelIndex("A");
            spec.z_channel = image.channelIndex("Z");
            spec.attribute("compression", "zip");
            writeWithOiio(tmp, spec, image.pixels().data(), OIIO::TypeDesc::FLOAT);
            return;
        }
        // 8-bit formats: R, G, B (and A) only.
        std::vector<int> src;
        for (const char* n : {"R", "G", "B"}) src.push_back(image.requireChannel(n));
        if (image.hasChannel("A")) src.push_back(image.channelIndex("A"));
        const int nc = static_cast<int>(src.size());
        std::vector<unsigned char> bytes(image.pixelCount() * nc);
        for (std::size_t p = 0; p < image.pixelCount(); ++p)
            for (int c = 0; c < nc; ++c) {
                float v = image.at(p, src[c]);
                v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;  // NaN -> 0
                bytes[p * nc + c] = static_cast<unsigned char>(v * 255.0f + 0.5f);
            }
        OIIO::ImageSpec spec(image.width(), image.height(), nc, OIIO::TypeDesc::UINT8);
        if (nc == 4) spec.alpha_channel = 3;
        // zlib level 1: on a 1920x1080 error map (noisy, 2 MB) level 6, the default, takes
        // 0.45 s to level 1's 0.04 s, for a file 17 % smaller; these images are written once
        // per render or comparison and read by a browser.
        spec.attribute("png:compressionLevel", 1);
        writeWithOiio(tmp, spec, bytes.data(), OIIO::TypeDesc::UINT8);
    });
}

}  // namespace twinrender::core
