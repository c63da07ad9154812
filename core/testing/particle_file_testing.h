// What the particle file reader tests share: the OpenSPH ball beside the checkout, files
// written to the test temp dir, expected errors, and known particles for round trips.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/install_layout.h"
#include "core/particle_file.h"

namespace twinrender::core::particle_file_testing {
namespace fs = std::filesystem;

// The real OpenSPH output (data/opensph_ball/): a basalt ball, 10,648 particles.
inline fs::path ballPath() {
    return ::twinrender::core::sourceDir() / "data" / "opensph_ball" / "ball.ssf";
}

// A path in the test temp dir, unique per test so that parallel ctest runs do not collide.
inline fs::path tempFile(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return fs::path(::testing::TempDir()) / fmt::format("particle_file_{}_{}", info->name(), name);
}

inline fs::path writeFile(const std::string& name, const std::string& bytes) {
    const fs::path path = tempFile(name);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    EXPECT_TRUE(out.good()) << "cannot write " << path;
    return path;
}

inline std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// Expects readParticleFile(path) to throw InputError whose message contains every part.
inline void expectInputError(const fs::path& path, const std::vector<std::string>& parts) {
    try {
        readParticleFile(path);
        ADD_FAILURE() << "no InputError for " << path;
    } catch (const InputError& e) {
        const std::string message = e.what();
        for (const std::string& part : parts)
            EXPECT_NE(message.find(part), std::string::npos)
                << "message lacks \"" << part << "\": " << message;
    }
}

inline double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

// Appends v in the given byte order.
template <typename T>
inline void put(std::string& out, T v, bool bigEndian = false) {
    using U = std::conditional_t<
        sizeof(T) == 1, std::uint8_t,
        std::conditional_t<sizeof(T) == 2, std::uint16_t,
                           std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
    const U u = std::bit_cast<U>(v);
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        const std::size_t shift = 8 * (bigEndian ? sizeof(T) - 1 - i : i);
        out += static_cast<char>((u >> shift) & 0xFF);
    }
}

// Known particles for the round trips: values a float holds exactly, so that a float PLY
// property reads back bit-exact too.
struct Known {
    std::vector<glm::dvec3> position;
    std::vector<double> h, mass, density, u, v, temperature;
    std::vector<std::int64_t> body;
};

inline Known knownParticles(std::size_t n) {
    Known k;
    for (std::size_t i = 0; i < n; ++i) {
        const double s = static_cast<double>(i);
        k.position.emplace_back(0.5 * s - 3.25, -1.125 * s, 1024.0 + 0.0625 * s);
        k.h.push_back(0.25 + 0.125 * s);
        k.mass.push_back(1.5e3 + s);
        k.density.push_back(2700.0 - 8.0 * s);
        k.u.push_back(s / 8.0);
        k.v.push_back(1.0 - s / 16.0);
        k.temperature.push_back(300.0 + 100.0 * s);
        k.body.push_back(static_cast<std::int64_t>(i % 3));
    }
    return k;
}

inline void expectMatches(const ParticleFileData& d, const Known& k, bool withOptional) {
    ASSERT_EQ(d.size(), k.position.size());
    ASSERT_EQ(d.h.size(), k.h.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
        EXPECT_EQ(d.position[i], k.position[i]) << "particle " << i;
        EXPECT_EQ(d.h[i], k.h[i]) << "particle " << i;
    }
    if (!withOptional) {
        EXPECT_TRUE(d.mass.empty());
        EXPECT_TRUE(d.density.empty());
        EXPECT_TRUE(d.uv.empty());
        EXPECT_TRUE(d.temperature.empty());
        EXPECT_TRUE(d.body.empty());
        return;
    }
    ASSERT_EQ(d.mass.size(), d.size());
    ASSERT_EQ(d.density.size(), d.size());
    ASSERT_EQ(d.uv.size(), d.size());
    ASSERT_EQ(d.temperature.size(), d.size());
    ASSERT_EQ(d.body.size(), d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
        EXPECT_EQ(d.mass[i], k.mass[i]) << "particle " << i;
        EXPECT_EQ(d.density[i], k.density[i]) << "particle " << i;
        EXPECT_EQ(d.uv[i], glm::dvec2(k.u[i], k.v[i])) << "particle " << i;
        EXPECT_EQ(d.temperature[i], k.temperature[i]) << "particle " << i;
        EXPECT_EQ(d.body[i], k.body[i]) << "particle " << i;
    }
}

}  // namespace twinrender::core::particle_file_testing
