// The particle-file targets' shared body: a file read as a scene's body is (core/particles.h:
// the reader, the scale to float scene units, the derived attributes), then everything that
// is built over the particles before a frame: the real-time renderer's radii, occlusion
// culling and ellipsoids, and a small raymarched frame (acceleration structures, traced rays).
#pragma once

#include <string>
#include <string_view>

namespace twinrender::fuzz {

// `extension` chooses the reader (".ssf", ".ply", ".csv").
void runParticlePipeline(std::string_view bytes, const std::string& extension);

}  // namespace twinrender::fuzz
