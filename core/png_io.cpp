#include "core/png_io.h"

#include <fmt/format.h>
#include <png.h>

#include <bit>
#include <cerrno>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"

namespace twinrender::core {

namespace fs = std::filesystem;

namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors by longjmp to the setjmp of the function that called it; the
// functions that call setjmp (decode, encode) hold no C++ object that needs destroying, and
// everything they fill lives in their caller.
struct Context {
    std::string error;
};

void onError(png_structp png, png_const_charp message) {
    static_cast<Context*>(png_get_error_ptr(png))->error = message;
    png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}  // ancillary chunk trouble; the pixels stand

// ---- Reading -------------------------------------------------------------------------------

struct Decoded {
    png_uint_32 width = 0, height = 0;
    int bitDepth = 0, channels = 0;
    bool gammaWithAlpha = false;  // left to OpenImageIO (readPng)
    std::vector<unsigned char> bytes;
    std::vector<png_bytep> rows;
};

// Reads the whole image into out.bytes (16-bit values in the machine's byte order). False
// after a libpng error (ctx.error says which).
bool decode(png_structp png, png_infop info, std::FILE* file, Decoded& out) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_read_info(png, info);
    int colourType = 0, interlace = 0;
    png_get_IHDR(png, info, &out.width, &out.height, &out.bitDepth, &colourType, &interlace,
                 nullptr, nullptr);
    // Before allocating: a damaged header may ask for any size (4 channels at most). No
    // object with a destructor may live across png_error's longjmp.
    if (!imageSizeError(out.width, out.height, 1.0, 4.0).empty())
        png_error(png,
                  "the image is over 16384 pixels a side or 268435456 values in all (the "
                  "header may be damaged)");
    const bool alpha =
        (colourType & PNG_COLOR_MASK_ALPHA) || png_get_valid(png, info, PNG_INFO_tRNS);
    if (alpha && png_get_valid(png, info, PNG_INFO_gAMA)) {
        out.gammaWithAlpha = true;
        return true;
    }
    png_set_expand(png);  // palette -> RGB, grey 1-4 bits -> 8, tRNS -> alpha
    if (out.bitDepth == 16 && std::endian::native == std::endian::little) png_set_swap(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    out.bitDepth = png_get_bit_depth(png, info);
    out.channels = png_get_channels(png, info);
    const std::size_t rowBytes = png_get_rowbytes(png, info);
    reserveHugePages(out.bytes, rowBytes * out.height);
    out.bytes.resize(rowBytes * out.height);
    out.rows.resize(out.height);
    for (png_uint_32 y = 0; y < out.height; ++y) out.rows[y] = out.bytes.data() + y * rowBytes;
    png_read_image(png, out.rows.data());
    png_read_end(png, nullptr);
    return true;
}

// Integer values to floats, colour premultiplied by alpha (the last channel when there are 2
// or 4) as OpenImageIO's PNG reader does: c * a / max, rounded down.
template <typename T>
void toFloat(const T* in, std::size_t pixels, int channels, float* out) {
    constexpr unsigned MAX = (1u << (8 * sizeof(T))) - 1u;
    constexpr float SCALE = 1.0f / static_cast<float>(MAX);  // OpenImageIO's v * (1 / max)
    const std::size_t n = pixels * channels;
    if (channels % 2 == 1) {
        for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<float>(in[i]) * SCALE;
        return;
    }
    for (std::size_t p = 0; p < pixels; ++p) {
        const T* px = in + p * channels;
        const unsigned a = px[channels - 1];
        for (int c = 0; c + 1 < channels; ++c)
            out[p * channels + c] = static_cast<float>(px[c] * a / MAX) * SCALE;
        out[p * channels + channels - 1] = static_cast<float>(a) * SCALE;
    }
}

// ---- Writing ---------------------------------------------------------------------------------

bool encode(png_structp png, png_infop info, std::FILE* file, int width, int height, int channels,
            png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_set_IHDR(png, info, width, height, 8,
                 channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 1);
    // No row filter: faster than libpng's adaptive choice for files of about the same size
    // (docs/performance.md, "Writing PNGs").
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    return true;
}

}  // namespace

bool isPngFile(const fs::path& path) {
    const File file(std::fopen(path.c_str(), "rb"));
    png_byte signature[8];
    return file && std::fread(signature, 1, 8, file.get()) == 8 &&
           png_sig_cmp(signature, 0, 8) == 0;
}

std::optional<DecodedPixels> readPng(const fs::path& path) {
    const File file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw InputError(fmt::format("{}: cannot read the image ({}); check the path",
                                     path.string(), std::strerror(errno)));
    Context ctx;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, onError, onWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    Decoded decoded;
    const bool ok = info && decode(png, info, file.get(), decoded);
    png_destroy_read_struct(&png, &info, nullptr);
    if (!ok)
        throw InputError(
            fmt::format("{}: the PNG cannot be read ({}); the file may be truncated "
                        "or not a PNG",
                        path.string(), ctx.error.empty() ? "out of memory" : ctx.error));
    if (decoded.gammaWithAlpha) return std::nullopt;

    DecodedPixels out;
    out.width = static_cast<int>(decoded.width);
    out.height = static_cast<int>(decoded.height);
    out.channelNames.assign(decoded.channels, "");
    const std::size_t pixels = static_cast<std::size_t>(decoded.width) * decoded.height;
    reserveHugePages(out.values, pixels * decoded.channels);
    out.values.resize(pixels * decoded.channels);
    if (decoded.bitDepth == 16)
        toFloat(reinterpret_cast<const std::uint16_t*>(decoded.bytes.data()), pixels,
                decoded.channels, out.values.data());
    else
        toFloat(decoded.bytes.data(), pixels, decoded.channels, out.values.data());
    return out;
}

void writePng(const fs::path& path, int width, int height, int channels,
              const unsigned char* values, const fs::path& shownPath) {
    const std::string shown = (shownPath.empty() ? path : shownPath).string();
    File file(std::fopen(path.c_str(), "wb"));
    if (!file)
        throw OutputError(
            fmt::format("{}: cannot write the image ({}); check that its folder is writable and "
                        "its disk not full",
                        shown, std::strerror(errno)));
    std::vector<png_bytep> rows(static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        rows[y] = const_cast<png_bytep>(values) + static_cast<std::size_t>(y) * width * channels;
    Context ctx;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, onError, onWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    const bool ok = info && encode(png, info, file.get(), width, height, channels, rows.data());
    png_destroy_write_struct(&png, &info);
    const bool closed = std::fclose(file.release()) == 0;
    if (!ok || !closed)
        throw OutputError(
            fmt::format("{}: cannot write the image ({}); check that its folder is writable and "
                        "its disk not full",
                        shown, ok ? std::strerror(errno) : ctx.error));
}

}  // namespace twinrender::core
