// Every program variant's shaders, as the renderer composes them, pass Khronos' reference
// compiler (glslangValidator, Debian's glslang-tools) for OpenGL: one more compiler than the
// GL device the GL tests run on. It accepts what NVIDIA's compiler refuses in places (a
// qualified buffer member passed to an unqualified parameter), so it is no substitute for a
// GPU; skipped where it is not installed.
#include "realtime/program_variants.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <string>

#include "tests/scratch_dir.h"

namespace twinrender::realtime {
namespace {

TEST(ProgramVariants, EveryVariantPassesGlslang) {
    if (std::system("command -v glslangValidator >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "glslangValidator is not installed (apt install glslang-tools)";
    const auto dir = twinrender::testing::freshDir("glslang_variants");
    const IncludedFile user = passThroughSurfaceFilter();
    std::set<std::string> texts;
    std::string files;
    int n = 0;
    // Named by their file's extension, which tells glslangValidator the stage.
    auto write = [&](const std::string& file, const std::vector<std::string>& defines,
                     const IncludedFile* included) {
        const std::string text = composeShader(file, defines, included).text;
        if (!texts.insert(text).second) return;
        const auto path = dir / (std::to_string(n++) + "_" + file);
        std::ofstream(path) << text;
        files += " " + path.string();
    };
    // Each also with the defines of the conversion test modes (gl/conversions.h), as the shader
    // library prepends them: the counter and both modes in every stage.
    const std::vector<std::string> modes[] = {{},
                                              {"CONVERSIONS_SATURATE", "CONVERSIONS_COUNT"},
                                              {"CONVERSIONS_WRAP", "CONVERSIONS_COUNT"}};
    for (const std::vector<std::string>& mode : modes)
        for (const ProgramVariant& v : allProgramVariants()) {
            std::vector<std::string> defines = mode;
            defines.insert(defines.end(), v.defines.begin(), v.defines.end());
            if (!v.compute.empty()) {
                write(v.compute, defines, nullptr);
                continue;
            }
            write(v.vertex, defines, nullptr);
            write(v.fragment, defines, v.userShader ? &user : nullptr);
        }
    EXPECT_GT(n, 3 * 80);
    const std::string cmd = "glslangValidator" + files + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buffer[4096];
    while (std::size_t got = std::fread(buffer, 1, sizeof(buffer), pipe))
        output.append(buffer, got);
    EXPECT_EQ(pclose(pipe), 0) << output;
}

}  // namespace
}  // namespace twinrender::realtime
