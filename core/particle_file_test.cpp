#include "core/particle_file.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <functional>
#include <glm/geometric.hpp>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"

namespace twinrender::core {
namespace {
namespace fs = std::filesystem;

// The real OpenSPH output beside the checkout (SCENES.md): a basalt ball, 10,648 particles.
fs::path ballPath() {
    return fs::path(TWINRENDER_SOURCE_DIR) / ".." / "shared" / "data" / "opensph" / "ball.ssf";
}

// A path in the test temp dir, unique per test so that parallel ctest runs do not collide.
fs::path tempFile(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return fs::path(::testing::TempDir()) / fmt::format("particle_file_{}_{}", info->name(), name);
}

fs::path writeFile(const std::string& name, const std::string& bytes) {
    const fs::path path = tempFile(name);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    EXPECT_TRUE(out.good()) << "cannot write " << path;
    return path;
}

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// Expects readParticleFile(path) to throw InputError whose message contains every part.
void expectInputError(const fs::path& path, const std::vector<std::string>& parts) {
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

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

// Appends v in the given byte order.
template <typename T>
void put(std::string& out, T v, bool bigEndian = false) {
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

Known knownParticles(std::size_t n) {
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

void expectMatches(const ParticleFileData& d, const Known& k, bool withOptional) {
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

// ---------------------------------------------------------------------------------------------
// OpenSPH .ssf
// ---------------------------------------------------------------------------------------------

TEST(ParticleFile, SsfBallCountExtentsAndSmoothingLength) {
    ASSERT_TRUE(fs::exists(ballPath())) << ballPath() << " is missing (shared data)";
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
    // SCENES.md gives h ~ 97 m, rounded to metres.
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

// ---------------------------------------------------------------------------------------------
// CSV
// ---------------------------------------------------------------------------------------------

TEST(ParticleFile, CsvRoundTrip) {
    const Known k = knownParticles(7);
    // Shuffled column order, an ignored column, whitespace around commas, comments, CRLF.
    std::string text =
        "# written by particle_file_test\n"
        " body , x,y ,z, vx, h,m,rho,u,v,temperature\r\n";
    for (std::size_t i = 0; i < k.h.size(); ++i) {
        if (i == 3) text += "# a comment between rows\n\n";
        text += fmt::format("{} , {},{} ,{}, 99, {},{},{},{},{},{}\r\n", k.body[i], k.position[i].x,
                            k.position[i].y, k.position[i].z, k.h[i], k.mass[i], k.density[i],
                            k.u[i], k.v[i], k.temperature[i]);
    }
    expectMatches(readParticleFile(writeFile("all.csv", text)), k, true);

    // Only the required columns, full double precision (shortest round-trip form).
    std::string minimal = "x,y,z,h\n";
    Known irrational = k;
    for (std::size_t i = 0; i < k.h.size(); ++i) {
        irrational.position[i] *= std::numbers::pi;
        irrational.h[i] *= std::numbers::e;
        minimal += fmt::format("{},{},{},{}\n", irrational.position[i].x, irrational.position[i].y,
                               irrational.position[i].z, irrational.h[i]);
    }
    expectMatches(readParticleFile(writeFile("minimal.csv", minimal)), irrational, false);
}

TEST(ParticleFile, CsvNonPositiveOrNanSmoothingLengthThrowsWithLine) {
    const fs::path negative = writeFile("negative.csv", "# comment\nx,y,z,h\n0,0,0,1\n1,2,3,-1\n");
    expectInputError(negative, {negative.string() + ":4:", "h = -1"});
    const fs::path zero = writeFile("zero.csv", "x,y,z,h\n0,0,0,0\n");
    expectInputError(zero, {zero.string() + ":2:", "h = 0"});
    const fs::path nan = writeFile("nan.csv", "x,y,z,h\n0,0,0,1\n\n0,0,0,1\n1,1,1,NaN\n");
    expectInputError(nan, {nan.string() + ":5:", "h = nan"});
    const fs::path inf = writeFile("inf.csv", "x,y,z,h\n0,0,0,inf\n");
    expectInputError(inf, {inf.string() + ":2:", "h = inf"});
}

TEST(ParticleFile, CsvNonFinitePositionThrowsWithLine) {
    const fs::path path = writeFile("pos.csv", "x,y,z,h\n0,0,0,1\n0,nan,0,1\n");
    expectInputError(path, {path.string() + ":3:", "position"});
}

TEST(ParticleFile, CsvMissingSmoothingLengthColumnThrowsNamingH) {
    const fs::path path = writeFile("noh.csv", "# no h\nx, y, z, rho\n0,0,0,1\n");
    expectInputError(path, {path.string() + ":2:", "no column 'h'"});
}

TEST(ParticleFile, CsvBadCellThrowsWithLineAndColumn) {
    const fs::path bad = writeFile("bad.csv", "x,y,z,h,rho\n0,0,0,1,2\n0,0,0,1,abc\n");
    expectInputError(bad, {bad.string() + ":3:", "'rho'", "column 5", "'abc'"});
    const fs::path count = writeFile("count.csv", "x,y,z,h\n0,0,0,1\n0,0,0\n");
    expectInputError(count, {count.string() + ":3:", "expected 4 columns", "found 3"});
    const fs::path body = writeFile("body.csv", "x,y,z,h,body\n0,0,0,1,1.5\n");
    expectInputError(body, {body.string() + ":2:", "body = 1.5"});
    const fs::path onlyU = writeFile("onlyu.csv", "x,y,z,h,u\n0,0,0,1,0.5\n");
    expectInputError(onlyU, {onlyU.string() + ":1:", "'v'"});
}

TEST(ParticleFile, CsvWithoutParticlesThrows) {
    const fs::path header = writeFile("header.csv", "x,y,z,h\n# nothing else\n");
    expectInputError(header, {header.string(), "no particles"});
    const fs::path comments = writeFile("comments.csv", "# only a comment\n");
    expectInputError(comments, {comments.string(), "no header"});
}

// ---------------------------------------------------------------------------------------------
// PLY
// ---------------------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------------------
// Any format
// ---------------------------------------------------------------------------------------------

TEST(ParticleFile, EmptyFilesThrow) {
    for (const char* name : {"empty.ssf", "empty.ply", "empty.csv"}) {
        const fs::path path = writeFile(name, "");
        expectInputError(path, {path.string(), "empty"});
    }
    const fs::path noVertices = writeFile("none.ply",
                                          "ply\nformat ascii 1.0\nelement vertex 0\n"
                                          "property float x\nproperty float y\n"
                                          "property float z\nproperty float h\nend_header\n");
    expectInputError(noVertices, {noVertices.string(), "no particles"});
}

TEST(ParticleFile, UnknownExtensionThrowsListingSupported) {
    const fs::path path = writeFile("particles.xyz", "0 0 0 1\n");
    expectInputError(path, {path.string(), "'.xyz'", ".ssf", ".ply", ".csv"});
}

TEST(ParticleFile, MissingFileThrows) {
    const fs::path path = tempFile("does_not_exist.csv");
    expectInputError(path, {path.string(), "no such"});
}

}  // namespace
}  // namespace twinrender::core
