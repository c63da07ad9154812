// CSV particle files: a header row naming the columns x y z h and optional m rho u v
// temperature body, then one particle per row.
#pragma once

#include <filesystem>

#include "core/particle_file.h"

namespace twinrender::core::particle_io {

// Throws InputError as readParticleFile says, naming a row by its line.
ParticleFileData readCsv(const std::filesystem::path& path);

}  // namespace twinrender::core::particle_io
