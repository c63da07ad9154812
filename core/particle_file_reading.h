// What the particle file readers (ssf_reader.h, ply_reader.h, csv_reader.h) share: reading a
// whole file, decoding numbers stored in a given byte order, and the check of what every
// reader must deliver.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "core/particle_file.h"

namespace twinrender::core::particle_io {

// The file's bytes; throws InputError naming the file when it cannot be opened or read.
std::string readWholeFile(const std::filesystem::path& path);

// Unsigned integer of the same size as T, to assemble T from bytes in a given order.
template <std::size_t N>
struct UnsignedOfSize;
template <>
struct UnsignedOfSize<1> {
    using Type = std::uint8_t;
};
template <>
struct UnsignedOfSize<2> {
    using Type = std::uint16_t;
};
template <>
struct UnsignedOfSize<4> {
    using Type = std::uint32_t;
};
template <>
struct UnsignedOfSize<8> {
    using Type = std::uint64_t;
};

// Decodes a T stored with the given byte order, independent of the host's order.
template <typename T>
T loadBytes(const unsigned char* p, bool bigEndian) {
    using U = typename UnsignedOfSize<sizeof(T)>::Type;
    U u = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        const std::size_t shift = 8 * (bigEndian ? sizeof(T) - 1 - i : i);
        u = static_cast<U>(u | (static_cast<U>(p[i]) << shift));
    }
    return std::bit_cast<T>(u);
}

// Checks what every reader must deliver (at least one particle; finite positions; finite h > 0;
// m, rho > 0, temperature >= 0 and finite uv where given). `where(i)` names particle i as the
// user finds it in the file, e.g. "ball.ssf: particle 17" or "dump.csv:19: particle 17".
void validateParticles(const ParticleFileData& d, const std::filesystem::path& path,
                       const std::function<std::string(std::size_t)>& where);

}  // namespace twinrender::core::particle_io
