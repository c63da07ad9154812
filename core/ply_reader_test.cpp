// PLY, through readParticleFile.
#include "core/ply_reader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "core/particle_file.h"
#include "core/testing/particle_file_testing.h"

namespace twinrender::core {
namespace {
namespace fs = std::filesystem;
using namespace particle_file_testing;

TEST(ParticleFile, PlyAsciiRoundTrip) {
    const Known k = knownParticles(5);
    // An element before the vertices, ignored properties (a scalar and a list) and a face
    // element after them: all must be skipped token by token.
    std::string text =
        "ply\nformat ascii 1.0\ncomment written by particle_file_test\n"
        "element camera 1\nproperty float fov\nproperty list uchar float clip\n"
        "element vertex 5\n"
        "property double x\nproperty double y\nproperty double z\n"
        "property uchar red\nproperty list uchar int neighbours\n"
        "property float h\nproperty double m\nproperty double rho\n"
        "property float u\nproperty float v\nproperty float temperature\n"
        "property int body\n"
        "element face 2\nproperty list uchar int vertex_indices\n"
        "end_header\n"
        "40.0 2 0.1 100\n";
    for (std::size_t i = 0; i < k.h.size(); ++i)
        text += fmt::format("{} {} {} 255 {} {} {} {} {} {} {} {}\n", k.position[i].x,
                            k.position[i].y, k.position[i].z, i == 2 ? "3 1 2 3" : "0", k.h[i],
                            k.mass[i], k.density[i], k.u[i], k.v[i], k.temperature[i], k.body[i]);
    text += "3 0 1 2\n3 2 3 4\n";
    expectMatches(readParticleFile(writeFile("ascii.ply", text)), k, true);
}

// A binary PLY with the known particles, mixed types and elements to skip around the vertices.
std::string binaryPly(const Known& k, bool bigEndian) {
    std::string out = fmt::format(
        "ply\r\nformat {} 1.0\r\n"
        "element meta 2\r\nproperty short a\r\nproperty double b\r\n"
        "element vertex {}\r\n"
        "property float x\r\nproperty float y\r\nproperty double z\r\n"
        "property list uchar int neighbours\r\nproperty double h\r\n"
        "property float m\r\nproperty double rho\r\nproperty ushort red\r\n"
        "property double u\r\nproperty double v\r\nproperty float temperature\r\n"
        "property uchar body\r\n"
        "element face 1\r\nproperty list int uint vertex_indices\r\n"
        "end_header\r\n",
        bigEndian ? "binary_big_endian" : "binary_little_endian", k.h.size());
    for (int i = 0; i < 2; ++i) {
        put<std::int16_t>(out, -7, bigEndian);
        put<double>(out, 1e300, bigEndian);
    }
    for (std::size_t i = 0; i < k.h.size(); ++i) {
        put(out, static_cast<float>(k.position[i].x), bigEndian);
        put(out, static_cast<float>(k.position[i].y), bigEndian);
        put(out, k.position[i].z, bigEndian);
        put<std::uint8_t>(out, static_cast<std::uint8_t>(i % 3), bigEndian);
        for (std::size_t j = 0; j < i % 3; ++j) put<std::int32_t>(out, -1, bigEndian);
        put(out, k.h[i], bigEndian);
        put(out, static_cast<float>(k.mass[i]), bigEndian);
        put(out, k.density[i], bigEndian);
        put<std::uint16_t>(out, 65535, bigEndian);
        put(out, k.u[i], bigEndian);
        put(out, k.v[i], bigEndian);
        put(out, static_cast<float>(k.temperature[i]), bigEndian);
        put<std::uint8_t>(out, static_cast<std::uint8_t>(k.body[i]), bigEndian);
    }
    put<std::int32_t>(out, 3, bigEndian);
    for (std::uint32_t j = 0; j < 3; ++j) put(out, j, bigEndian);
    return out;
}

TEST(ParticleFile, PlyBinaryRoundTrip) {
    const Known k = knownParticles(9);
    expectMatches(readParticleFile(writeFile("little.ply", binaryPly(k, false))), k, true);
    expectMatches(readParticleFile(writeFile("big.ply", binaryPly(k, true))), k, true);
}

TEST(ParticleFile, PlyTruncatedBinaryThrowsNamingVertex) {
    const std::string full = binaryPly(knownParticles(9), false);
    // The face element takes the last 16 bytes; cutting 40 more lands inside the vertices.
    const fs::path path = writeFile("cut.ply", full.substr(0, full.size() - 56));
    expectInputError(path, {path.string(), "truncated", "vertex 8"});
}

TEST(ParticleFile, PlyMissingPropertyThrowsNamingHeaderLine) {
    const fs::path noH = writeFile("noh.ply",
                                   "ply\nformat ascii 1.0\ncomment no h\nelement vertex 1\n"
                                   "property float x\nproperty float y\nproperty float z\n"
                                   "end_header\n0 0 0\n");
    expectInputError(noH, {noH.string(), "header line 4", "'h'"});
    const fs::path badType = writeFile("type.ply",
                                       "ply\nformat ascii 1.0\nelement vertex 1\n"
                                       "property float x\nproperty quad y\nend_header\n");
    expectInputError(badType, {badType.string(), "header line 5", "'quad'"});
}

TEST(ParticleFile, PlyBadValuesThrowNamingVertex) {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nproperty float h\n"
        "end_header\n";
    const fs::path h = writeFile("h.ply", header + "0 0 0 1\n0 0 0 1\n0 0 0 -2\n");
    expectInputError(h, {h.string(), "vertex 2", "h = -2"});
    const fs::path text = writeFile("text.ply", header + "0 0 0 1\n0 zero 0 1\n0 0 0 1\n");
    expectInputError(text, {text.string(), "vertex 1", "line 10", "'zero'"});
    const fs::path shortData = writeFile("short.ply", header + "0 0 0 1\n0 0 0\n");
    expectInputError(shortData, {shortData.string(), "truncated", "vertex 1"});
}

}  // namespace
}  // namespace twinrender::core
