// Any format: the choice of the reader and the checks before it.
#include "core/particle_file.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

#include "core/testing/particle_file_testing.h"

namespace twinrender::core {
namespace {
namespace fs = std::filesystem;
using namespace particle_file_testing;

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

TEST(ParticleFile, EveryFormatIsChosenByItsExtensionInAnyCase) {
    std::vector<std::string> listed = {"particles.xyz"};
    for (const ParticleFileFormat& format : particleFileFormats()) {
        ASSERT_TRUE(format.extension.starts_with('.')) << format.extension;
        listed.emplace_back(format.extension);
        if (!format.description.empty()) listed.push_back(fmt::format("({})", format.description));
        // An upper-case extension reaches the format's reader, which rejects the file's text.
        std::string upper(format.extension);
        for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        const fs::path path = writeFile("upper" + upper, "not particles\n");
        try {
            readParticleFile(path);
            ADD_FAILURE() << "no InputError for " << path;
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).find("unknown particle file extension"),
                      std::string::npos)
                << e.what();
        }
    }
    expectInputError(writeFile("particles.xyz", "0 0 0 1\n"), listed);
}

TEST(ParticleFile, MissingFileThrows) {
    const fs::path path = tempFile("does_not_exist.csv");
    expectInputError(path, {path.string(), "no such"});
}

}  // namespace
}  // namespace twinrender::core
