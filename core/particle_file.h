// Particles written by other software: OpenSPH binary output (.ssf, the format of OpenSPH's
// core/io/Output.cpp, BinaryOutput), PLY (ascii and binary little-endian) and CSV.
// CSV and PLY columns / vertex properties: x y z h, optional m rho u v temperature body.
// One reader per format (ssf_reader.h, ply_reader.h, csv_reader.h), chosen by the file's
// extension from particleFileFormats().
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <string_view>
#include <vector>

namespace twinrender::core {

struct ParticleFileData {
    std::vector<glm::dvec3> position;  // file units
    std::vector<double> h;             // smoothing length, file units, finite and > 0
    std::vector<double> mass;          // empty when the file has none
    std::vector<double> density;       // empty when the file has none
    std::vector<glm::dvec2> uv;        // empty when the file has none
    std::vector<double> temperature;   // kelvin; empty when the file has none
    std::vector<std::int64_t> body;    // body / flag index; empty when the file has none

    std::size_t size() const { return position.size(); }
};

// Reads by extension (.ssf, .ply, .csv). Throws InputError naming the file (and the line or
// particle index) for an unreadable, truncated or malformed file, a missing required column,
// or a NaN, infinite or non-positive h or position.
ParticleFileData readParticleFile(const std::filesystem::path& path);

// The reader of one file format. It gets an existing, non-empty regular file and throws
// InputError as readParticleFile says.
struct ParticleFileFormat {
    std::string_view extension;    // lower case, with its dot
    std::string_view description;  // for the list of supported formats; may be empty
    ParticleFileData (*read)(const std::filesystem::path& path);
};

// The formats readParticleFile reads, in the order its messages list them.
std::span<const ParticleFileFormat> particleFileFormats();

}  // namespace twinrender::core
