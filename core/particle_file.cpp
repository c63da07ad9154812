#include "core/particle_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "core/csv_reader.h"
#include "core/error.h"
#include "core/ply_reader.h"
#include "core/ssf_reader.h"

namespace twinrender::core {
namespace fs = std::filesystem;

namespace {

// A new format is a reader of its own (<format>_reader.h/.cpp) and a line here.
constexpr ParticleFileFormat FORMATS[] = {
    {".ssf", "OpenSPH binary output", particle_io::readSsf},
    {".ply", "ascii or binary", particle_io::readPly},
    {".csv", "", particle_io::readCsv},
};

// ".ssf (OpenSPH binary output), .ply (ascii or binary) and .csv".
std::string supportedFormats() {
    std::string list;
    const std::size_t n = std::size(FORMATS);
    for (std::size_t i = 0; i < n; ++i) {
        if (i > 0) list += i + 1 < n ? ", " : " and ";
        list += FORMATS[i].extension;
        if (!FORMATS[i].description.empty()) list += fmt::format(" ({})", FORMATS[i].description);
    }
    return list;
}

}  // namespace

std::span<const ParticleFileFormat> particleFileFormats() {
    return FORMATS;
}

ParticleFileData readParticleFile(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const auto format =
        std::find_if(std::begin(FORMATS), std::end(FORMATS),
                     [&](const ParticleFileFormat& f) { return f.extension == ext; });
    if (format == std::end(FORMATS))
        throw InputError(fmt::format("{}: unknown particle file extension '{}'; supported are {}",
                                     path.string(), ext, supportedFormats()));
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (!fs::exists(status))
        throw InputError(fmt::format("{}: no such particle file; check the path", path.string()));
    if (!fs::is_regular_file(status))
        throw InputError(
            fmt::format("{}: not a regular file; give a particle file", path.string()));
    if (fs::file_size(path, ec) == 0 && !ec)
        throw InputError(
            fmt::format("{}: the file is empty; give a file with particles", path.string()));
    return format->read(path);
}

}  // namespace twinrender::core
