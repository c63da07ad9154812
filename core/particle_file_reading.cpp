#include "core/particle_file_reading.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>

#include "core/error.h"

namespace twinrender::core::particle_io {
namespace fs = std::filesystem;

std::string readWholeFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(
            fmt::format("{}: cannot open the particle file; check the path", path.string()));
    std::string bytes;
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    if (size < 0)
        throw InputError(
            fmt::format("{}: cannot read the particle file; check the path", path.string()));
    bytes.resize(static_cast<std::size_t>(size));
    if (!in.read(bytes.data(), size))
        throw InputError(
            fmt::format("{}: reading the particle file failed after {} of {} bytes; "
                        "check the disk and the file",
                        path.string(), in.gcount(), size));
    return bytes;
}

void validateParticles(const ParticleFileData& d, const fs::path& path,
                       const std::function<std::string(std::size_t)>& where) {
    if (d.size() == 0)
        throw InputError(fmt::format("{}: the file holds no particles; write at least one particle",
                                     path.string()));
    const std::string fix = "fix the file or drop the particle";
    for (std::size_t i = 0; i < d.size(); ++i) {
        const glm::dvec3& p = d.position[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError(fmt::format("{} has a non-finite position ({}, {}, {}); {}", where(i),
                                         p.x, p.y, p.z, fix));
        if (!std::isfinite(d.h[i]) || d.h[i] <= 0.0)
            throw InputError(
                fmt::format("{} has smoothing length h = {}; h must be finite and > 0: {}",
                            where(i), d.h[i], fix));
        // Volume = m / rho feeds the colour field: both must be positive and finite.
        if (!d.mass.empty() && !(std::isfinite(d.mass[i]) && d.mass[i] > 0.0))
            throw InputError(fmt::format("{} has mass m = {}; m must be finite and > 0: {}",
                                         where(i), d.mass[i], fix));
        if (!d.density.empty() && !(std::isfinite(d.density[i]) && d.density[i] > 0.0))
            throw InputError(fmt::format("{} has density rho = {}; rho must be finite and > 0: {}",
                                         where(i), d.density[i], fix));
        if (!d.temperature.empty() && !(std::isfinite(d.temperature[i]) && d.temperature[i] >= 0.0))
            throw InputError(
                fmt::format("{} has temperature = {} K; it must be finite and >= 0: {}", where(i),
                            d.temperature[i], fix));
        if (!d.uv.empty() && !(std::isfinite(d.uv[i].x) && std::isfinite(d.uv[i].y)))
            throw InputError(fmt::format("{} has non-finite texture coordinates ({}, {}); {}",
                                         where(i), d.uv[i].x, d.uv[i].y, fix));
    }
}

}  // namespace twinrender::core::particle_io
