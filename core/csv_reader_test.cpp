// CSV, through readParticleFile.
#include "core/csv_reader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "core/particle_file.h"
#include "core/testing/particle_file_testing.h"

namespace twinrender::core {
namespace {
namespace fs = std::filesystem;
using namespace particle_file_testing;

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

// Volume = m / rho feeds the colour field: a negative mass or a zero density is rejected
// naming the line, the particle and the value.
TEST(ParticleFile, CsvNonPositiveMassOrDensityThrowsWithLine) {
    const fs::path mass = writeFile("mass.csv", "x,y,z,h,m,rho\n0,0,0,1,1,1\n1,0,0,1,-2,1\n");
    expectInputError(mass, {mass.string() + ":3: particle 1", "m = -2"});
    const fs::path rho = writeFile("rho.csv", "x,y,z,h,m,rho\n0,0,0,1,1,0\n");
    expectInputError(rho, {rho.string() + ":2: particle 0", "rho = 0"});
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

}  // namespace
}  // namespace twinrender::core
