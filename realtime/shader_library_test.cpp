#include "realtime/shader_library.h"

#include <gtest/gtest.h>

namespace twinrender::realtime {
namespace {

TEST(ShaderLibrary, EmbedsTheShaderFiles) {
    for (const char* name : {"common.glsl", "impostor.vert", "gbuffer.frag", "shadow.frag",
                             "ssss.frag", "shade.frag", "composite.frag", "fullscreen.vert"})
        EXPECT_FALSE(shaderFile(name).empty()) << name;
    EXPECT_THROW(shaderFile("missing.frag"), std::exception);
}

TEST(ShaderLibrary, ComposesVersionDefinesAndIncludesOnce) {
    const std::vector<std::string> defines = {"DEPTH_LOG", "MAX_TAPS 4"};
    const gl::ShaderSource s = composeShader("shade.frag", defines);
    EXPECT_EQ(s.text.rfind("#version 450 core\n#define DEPTH_LOG\n#define MAX_TAPS 4\n", 0), 0u);
    EXPECT_EQ(s.text.find("#include"), std::string::npos);
    // common.glsl is included by shade.frag directly; its block appears once.
    const auto first = s.text.find("uniform FrameUniforms");
    ASSERT_NE(first, std::string::npos);
    EXPECT_EQ(s.text.find("uniform FrameUniforms", first + 1), std::string::npos);
    ASSERT_GE(s.files.size(), 4u);
    EXPECT_EQ(s.files[1], "shade.frag");
    // Line 4 of the text (after the version and two defines) is shade.frag's first line.
    ASSERT_GE(s.spans.size(), 2u);
    EXPECT_EQ(s.spans[1].firstLine, 4);
    EXPECT_EQ(s.spans[1].file, 1);
    EXPECT_EQ(s.spans[1].fileLine, 1);
}

}  // namespace
}  // namespace twinrender::realtime
