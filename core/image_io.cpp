#include "core/image_io.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace twinrender::core {
namespace fs = std::filesystem;
namespace OIIO = OIIO_NAMESPACE;

namespace {

OutputError cannotWrite(const fs::path& path, const std::string& why) {
    return OutputError(fmt::format(
        "{}: cannot write the file ({}); check that its folder is writable and its disk not full",
        path.string(), why));
}

}  // namespace

Image readImage(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in)
        throw InputError(fmt::format("{}: cannot read the image ({}); check the path and format",
                                     path.string(), OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
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

namespace {

// Writes `tmp`; errors name `path`, the file the user asked for.
void writeWithOiio(const fs::path& tmp, const fs::path& path, const OIIO::ImageSpec& spec,
                   const void* data, OIIO::TypeDesc dataType) {
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out || !out->open(tmp.string(), spec) || !out->write_image(dataType, data) ||
        !out->close())
        throw OutputError(
            fmt::format("{}: cannot write the image ({}); check that its folder is writable and "
                        "its disk not full",
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
            writeWithOiio(tmp, path, spec, image.pixels().data(), OIIO::TypeDesc::FLOAT);
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
        writeWithOiio(tmp, path, spec, bytes.data(), OIIO::TypeDesc::UINT8);
    });
}

}  // namespace twinrender::core
