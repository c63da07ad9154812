// OpenSPH binary output (.ssf): the format of OpenSPH's core/io/Output.cpp, BinaryOutput.
#pragma once

#include <filesystem>

#include "core/particle_file.h"

namespace twinrender::core::particle_io {

// Positions, h and, where the file has them, mass, density, temperature, flag (as the body)
// and uvw (as uv) of every particle; attractors are not read. Throws InputError as
// readParticleFile says.
ParticleFileData readSsf(const std::filesystem::path& path);

}  // namespace twinrender::core::particle_io
