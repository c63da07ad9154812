// Fuzz targets ssf, ply and csv: a particle file through the reader, the derived attributes
// and the structures both renderers build over the particles (particle_pipeline.h). Built once
// per format with PARTICLE_FILE_EXTENSION set to the reader's extension (fuzz/CMakeLists.txt).
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_support.h"
#include "fuzz/particle_pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    twinrender::fuzz::runParticlePipeline(twinrender::fuzz::asText(data, size),
                                          PARTICLE_FILE_EXTENSION);
    return 0;
}
