#include "core/image_io.h"

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <exception>
#include <fstream>

#include "core/error.h"
#include "core/oiio_module.h"
#include "core/png_io.h"

namespace twinrender::core {
namespace fs = std::filesystem;

namespace {

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

}  // namespace

Image readImage(const fs::path& path) {
    // PNGs through libpng (png_io.h): such a process never loads OpenImageIO.
    if (isPngFile(path))
        if (std::optional<DecodedPixels> png = readPng(path)) return toImage(std::move(*png));
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

void writeImage(const Image& image, const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    writeFileAtomically(path, [&](const fs::path& tmp) {
        if (ext == ".exr") {
            check(path, oiio::api().writeFloat(tmp.string(), image.width(), image.height(),
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
            writePng(tmp, image.width(), image.height(), nc, bytes.data());
        else
            check(path, oiio::api().writeBytes(tmp.string(), image.width(), image.height(), nc,
                                               bytes.data()));
    });
}

}  // namespace twinrender::core
