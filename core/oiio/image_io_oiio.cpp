// The OpenImageIO module (core/oiio_module.h): built as the shared module twinrender_oiio,
// the only code that links OpenImageIO, loaded by the program on first use.
#include <OpenImageIO/imageio.h>

#include "core/oiio_module.h"

namespace twinrender::core::oiio {
namespace {

namespace OIIO = OIIO_NAMESPACE;

std::string read(const std::string& path, DecodedPixels& out) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return "cannot read the image (" + OIIO::geterror() + "); check the path and format";
    const OIIO::ImageSpec& spec = in->spec();
    // Before allocating: a damaged header may ask for any size.
    if (std::string error = imageSizeError(spec.width, spec.height, spec.depth, spec.nchannels);
        !error.empty())
        return error;
    out.width = spec.width;
    out.height = spec.height;
    out.isFloat = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                  spec.format.basetype == OIIO::TypeDesc::HALF;
    out.channelNames.assign(spec.nchannels, "");
    for (int c = 0; c < spec.nchannels && c < static_cast<int>(spec.channelnames.size()); ++c)
        out.channelNames[c] = spec.channelnames[c];
    out.values.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.values.data()))
        return "the image data cannot be read (" + in->geterror() + "); the file may be truncated";
    return {};
}

std::string write(const std::string& path, const OIIO::ImageSpec& spec, const void* values,
                  OIIO::TypeDesc type) {
    auto out = OIIO::ImageOutput::create(path);
    if (out && out->open(path, spec) && out->write_image(type, values) && out->close()) return {};
    return "cannot write the image (" + (out ? out->geterror() : OIIO::geterror()) +
           "); check that the folder is writable";
}

std::string writeFloat(const std::string& path, int width, int height,
                       const std::vector<std::string>& channelNames, int alpha, int z,
                       const float* values) {
    OIIO::ImageSpec spec(width, height, static_cast<int>(channelNames.size()),
                         OIIO::TypeDesc::FLOAT);
    spec.channelnames = channelNames;
    spec.alpha_channel = alpha;
    spec.z_channel = z;
    spec.attribute("compression", "zip");
    return write(path, spec, values, OIIO::TypeDesc::FLOAT);
}

std::string writeBytes(const std::string& path, int width, int height, int channels,
                       const unsigned char* values) {
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    if (channels == 4) spec.alpha_channel = 3;
    return write(path, spec, values, OIIO::TypeDesc::UINT8);
}

constexpr Api API = {read, writeFloat, writeBytes};

}  // namespace
}  // namespace twinrender::core::oiio

extern "C" __attribute__((visibility("default"))) const twinrender::core::oiio::Api*
twinrender_oiio_api() {
    return &twinrender::core::oiio::API;
}
