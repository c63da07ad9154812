// PLY particle files: vertices with properties x y z h and optional m rho u v temperature body.
#pragma once

#include <filesystem>

#include "core/particle_file.h"

namespace twinrender::core::particle_io {

// Throws InputError as readParticleFile says, naming a vertex by its index (and its line in an
// ascii file) and a header error by its line.
ParticleFileData readPly(const std::filesystem::path& path);

}  // namespace twinrender::core::particle_io
