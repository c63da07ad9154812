// OpenSPH .ssf, through readParticleFile.
#include "core/ssf_reader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>

#include "core/particle_file.h"
#include "core/testing/particle_file_testing.h"

namespace twinrender::core {
namespace {
namespace fs = std::filesystem;
using namespace particle_file_testing;

TEST(ParticleFile, SsfBallCountExtentsAndSmoothingLength) {
    ASSERT_TRUE(fs::exists(ballPath())) << ballPath() << " is missing (data/opensph_ball/)";
    const ParticleFileData d = readParticleFile(ballPath());
    EXPECT_EQ(d.size(), 10648u);
    ASSERT_EQ(d.h.size(), d.size());
    double maxRadius = 0.0;
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& p : d.position) {
        maxRadius = std::max(maxRadius, glm::length(p));
        mean += p / static_cast<double>(d.size());
    }
    // The ball has radius 1 km; the outermost lattice particle sits within about one lattice
    // spacing (h / 1.3 = 75 m) of the surface.
    EXPECT_NEAR(maxRadius, 1000.0, 75.0);
    // Centred at the origin: a lattice offset of at most a spacing.
    EXPECT_LT(glm::length(mean), 75.0);
    // The file's h is about 97 m, rounded to metres.
    EXPECT_NEAR(median(d.h), 97.0, 1.0);
    for (double h : d.h) ASSERT_GT(h, 0.0);
}

TEST(ParticleFile, SsfBallMassDensityAndFlag) {
    const ParticleFileData d = readParticleFile(ballPath());
    ASSERT_EQ(d.mass.size(), d.size());
    ASSERT_EQ(d.density.size(), d.size());
    double totalMass = 0.0;
    for (std::size_t i = 0; i < d.size(); ++i) {
        ASSERT_GT(d.mass[i], 0.0) << "particle " << i;
        // Initial conditions: every particle at basalt's reference density (kg/m^3).
        ASSERT_EQ(d.density[i], 2700.0) << "particle " << i;
        totalMass += d.mass[i];
    }
    // OpenSPH gives the particles equal shares of rho * (4/3) pi R^3 with R = 1000 m; the
    // relative tolerance covers the rounding of 10,648 summands.
    const double ballMass = 2700.0 * 4.0 / 3.0 * std::numbers::pi * 1e9;
    EXPECT_NEAR(totalMass / ballMass, 1.0, 1e-9);
    // One body: flag 0 everywhere.
    ASSERT_EQ(d.body.size(), d.size());
    EXPECT_TRUE(std::all_of(d.body.begin(), d.body.end(), [](std::int64_t b) { return b == 0; }));
    // The file stores specific energy, not temperature, and no texture coordinates.
    EXPECT_TRUE(d.temperature.empty());
    EXPECT_TRUE(d.uv.empty());
}

TEST(ParticleFile, SsfTruncatedThrowsNamingFileAndWhatWasExpected) {
    const std::string ball = readBytes(ballPath());
    ASSERT_GT(ball.size(), 1000000u);

    const fs::path half = writeFile("half.ssf", ball.substr(0, ball.size() / 2));
    expectInputError(half, {half.string(), "truncated: expected 10648 values of quantity '",
                            fmt::format("file has {} bytes", ball.size() / 2)});

    const fs::path header = writeFile("header.ssf", ball.substr(0, 100));
    expectInputError(header, {header.string(), "truncated", "header", "file has 100 bytes"});

    // 256-byte header plus part of the 13-entry quantity table.
    const fs::path table = writeFile("table.ssf", ball.substr(0, 300));
    expectInputError(table, {table.string(), "truncated", "13 quantities"});

    const fs::path lastByte = writeFile("last.ssf", ball.substr(0, ball.size() - 1));
    expectInputError(lastByte, {lastByte.string(), "truncated", "quantity 'flag'"});
}

TEST(ParticleFile, SsfUnknownVersionThrows) {
    std::string bytes = readBytes(ballPath());
    std::string version;
    put<std::int64_t>(version, 20990101);
    bytes.replace(44, 8, version);  // the version field of the 256-byte header
    const fs::path path = writeFile("future.ssf", bytes);
    expectInputError(path, {path.string(), "version 20990101", "20210808"});
}

TEST(ParticleFile, SsfNotOpenSphThrows) {
    const fs::path path = writeFile("text.ssf", "x,y,z,h\n0,0,0,1\n");
    expectInputError(path, {path.string(), "\"SPH\""});
}

}  // namespace
}  // namespace twinrender::core
