#include "core/image_io.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <tbb/parallel_invoke.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>

#include "core/error.h"
#include "core/oiio_module.h"
#include "core/png_io.h"
#include "core/write_roots.h"

namespace twinrender::core {
namespace fs = std::filesystem;

namespace {

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
        if (!imageSizeError(width, height, 1.0, std::max(channels, 1.0)).empty())
            throw corrupt(
                fmt::format("part {} has a data window of {} x {} pixels with {} "
                            "channels; images up to {} pixels a side and {:g} values "
                            "in all are read",
                            part, width, height, channels, MOST_IMAGE_SIDE, MOST_IMAGE_VALUES));
        if (!multipart || attributes == 0) return;
    }
}

// Names the channels (a plain image's by position, whatever the file says) and makes a grey
// image R = G = B.
Image toImage(DecodedPixels d) {
    std::vector<std::string> names = d.channelNames;
    for (std::size_t c = 0; c < names.size(); ++c)
        if (names[c].empty()) names[c] = fmt::format("channel{}", c);
    if (!d.isFloat) {
        static const char* kRgba[] = {"R", "G", "B", "A"};
        if (names.size() == 1)
            names = {"Y"};
        else
            for (std::size_t c = 0; c < names.size() && c < 4; ++c) names[c] = kRgba[c];
    }
    const int channels = static_cast<int>(names.size());
    Image image(d.width, d.height, std::move(names), std::move(d.values));
    // A grey image stands for R = G = B.
    if (!d.isFloat && channels <= 2) {
        Image rgb(d.width, d.height, {"R", "G", "B"});
        for (std::size_t p = 0; p < image.pixelCount(); ++p)
            for (int c = 0; c < 3; ++c) rgb.at(p, c) = image.at(p, 0);
        return rgb;
    }
    return image;
}

// Throws InputError naming the file when an OpenImageIO call said what went wrong.
void check(const fs::path& path, const std::string& error) {
    if (!error.empty()) throw InputError(fmt::format("{}: {}", path.string(), error));
}

OutputError cannotWrite(const fs::path& path, const std::string& why) {
    return OutputError(fmt::format(
        "{}: cannot write the file ({}); check that its folder is writable and its disk not full",
        path.string(), why));
}

// Throws OutputError naming `path` (the file the user asked for, not the temporary one
// written) when an OpenImageIO write said what went wrong.
void checkWrite(const fs::path& path, const std::string& error) {
    if (!error.empty()) throw cannotWrite(path, error);
}

}  // namespace

Image readImage(const fs::path& path) {
    // A device, pipe or folder: /dev/zero would be read for ever.
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw InputError(
            fmt::format("{}: not an image file (a device, pipe or folder); give "
                        "the path of an EXR or PNG file",
                        path.string()));
    // PNGs through libpng (png_io.h): such a process never loads OpenImageIO.
    if (isPngFile(path))
        if (std::optional<DecodedPixels> png = readPng(path)) return toImage(std::move(*png));
    if (fs::is_regular_file(status)) checkExrHeader(path);
    DecodedPixels decoded;
    check(path, oiio::api().read(path.string(), decoded));
    return toImage(std::move(decoded));
}

std::pair<Image, Image> readImages(const fs::path& first, const fs::path& second) {
    std::pair<Image, Image> images;
    std::exception_ptr errors[2];
    auto read = [](const fs::path& path, Image& image, std::exception_ptr& error) {
        try {
            image = readImage(path);
        } catch (...) {
            error = std::current_exception();
        }
    };
    tbb::parallel_invoke([&] { read(first, images.first, errors[0]); },
                         [&] { read(second, images.second, errors[1]); });
    for (const auto& error : errors)
        if (error) std::rethrow_exception(error);
    return images;
}

void writeFileAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    checkWriteAllowed(path);
    static std::atomic<unsigned> counter{0};
    fs::path tmp = path;
    tmp.replace_filename(fmt::format(".{}.tmp{}-{}{}", path.stem().string(), getpid(), counter++,
                                     path.extension().string()));
    const auto removeTmp = [&] {
        std::error_code ec;
        fs::remove(tmp, ec);
    };
    try {
        if (path.has_parent_path()) fs::create_directories(path.parent_path());
        write(tmp);
        fs::rename(tmp, path);
    } catch (const fs::filesystem_error& e) {
        removeTmp();
        throw cannotWrite(path, e.code().message());
    } catch (...) {
        removeTmp();
        throw;
    }
}

void writeTextFile(const fs::path& path, std::string_view text) {
    writeFileAtomically(path, [&](const fs::path& tmp) {
        // POSIX calls, not a stream: a full disk or a file size limit shows in write's and
        // close's result with its errno, where a stream only sets a flag.
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd < 0) throw cannotWrite(path, std::strerror(errno));
        for (std::size_t done = 0; done < text.size();) {
            const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) {
                const int error = errno;
                ::close(fd);
                throw cannotWrite(path, std::strerror(error));
            }
            done += static_cast<std::size_t>(n);
        }
        if (::close(fd) != 0) throw cannotWrite(path, std::strerror(errno));
    });
}

void writeImage(const Image& image, const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    writeFileAtomically(path, [&](const fs::path& tmp) {
        if (ext == ".exr") {
            checkWrite(path,
                       oiio::api().writeFloat(tmp.string(), image.width(), image.height(),
                                              image.channelNames(), image.channelIndex("A"),
                                              image.channelIndex("Z"), image.pixels().data()));
            return;
        }
        // 8-bit formats: R, G, B (and A) only.
        std::vector<int> src;
        for (const char* n : {"R", "G", "B"}) src.push_back(image.requireChannel(n));
        if (image.hasChannel("A")) src.push_back(image.channelIndex("A"));
        const int nc = static_cast<int>(src.size());
        std::vector<unsigned char> bytes;
        reserveHugePages(bytes, image.pixelCount() * nc);
        bytes.resize(image.pixelCount() * nc);
        for (std::size_t p = 0; p < image.pixelCount(); ++p)
            for (int c = 0; c < nc; ++c) {
                float v = image.at(p, src[c]);
                v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;  // NaN -> 0
                bytes[p * nc + c] = static_cast<unsigned char>(v * 255.0f + 0.5f);
            }
        if (ext == ".png")
            writePng(tmp, image.width(), image.height(), nc, bytes.data(), path);
        else
            checkWrite(path, oiio::api().writeBytes(tmp.string(), image.width(), image.height(), nc,
                                                    bytes.data()));
    });
}

}  // namespace twinrender::core
