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
#include <type_traits>

#include "core/particle_file.h"

namespace twinrender::core::particle_io {

// The file's bytes; throws InputError naming the file when it cannot be opened or read.
std::string readWholeFile(const std::filesystem::path& path);

// Unsigned integer of N bytes, to assemble a T of that size from bytes in a given order.
template <std::size_t N>
using UnsignedOfSize = std::conditional_t<
    N == 1, std::uint8_t,
    std::conditional_t<N == 2, std::uint16_t,
                       std::conditional_t<N == 4, std::uint32_t, std::uint64_t>>>;

// Decodes a T stored with the given byte order, independent of the host's order.
template <typename T>
T loadBytes(const unsigned char* p, bool bigEndian) {
    static_assert(sizeof(T) == 1 || sizeof(T) == 2 || sizeof(T) == 4 || sizeof(T) == 8);
    using U = UnsignedOfSize<sizeof(T)>;
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
