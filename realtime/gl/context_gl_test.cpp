#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "realtime/gl/buffer.h"
#include "realtime/gl/context.h"
#include "realtime/gl/error.h"
#include "realtime/gl/framebuffer.h"
#include "realtime/gl/poison.h"
#include "realtime/gl/program.h"
#include "realtime/gl/texture.h"
#include "realtime/gl/timer_query.h"

namespace twinrender::realtime::gl {
namespace {

TEST(Context, CreatesOpenGL45CoreAndNamesTheRenderer) {
    Context context;
    EXPECT_FALSE(context.renderer().empty());
    EXPECT_NE(context.version().find("4."), std::string::npos) << context.version();
    EXPECT_NE(context.description().find(context.renderer()), std::string::npos);
    std::cout << "[ renderer ] " << context.description() << "\n";
}

TEST(Context, ClearsAnRgba32fFramebufferAndReadsItBack) {
    Context context(ContextOptions{.debug = true});
    Texture colour(7, 5, Format::RGBA32F);
    Framebuffer fb("test", {{&colour}});
    fb.bind();
    const glm::vec4 value(0.25f, -1.5f, 1e20f, 3.0f);  // float targets keep any value
    fb.clearColor(0, value);
    const std::vector<float> pixels = fb.read(0, 4);
    ASSERT_EQ(pixels.size(), 7u * 5u * 4u);
    for (std::size_t i = 0; i < pixels.size(); i += 4) {
        EXPECT_EQ(pixels[i + 0], value.x);
        EXPECT_EQ(pixels[i + 1], value.y);
        EXPECT_EQ(pixels[i + 2], value.z);
        EXPECT_EQ(pixels[i + 3], value.w);
    }
    checkErrors("test");
}

// Poison mode (CTest runs the GL tests in it): a write past a storage buffer's end lands in the
// poison tail, where overrun() sees it; on a GPU it would land in other memory. A read past the
// end reads the poison word, not llvmpipe's zero.
TEST(Context, PoisonModeSeesAccessPastABuffersEnd) {
    if (!poisonMode()) GTEST_SKIP() << "needs TWINRENDER_GL_POISON=1; CTest runs it that way";
    Context context(ContextOptions{.debug = true});
    const Program program("past_the_end", ShaderSource{.text = R"(#version 450
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Data { uint data[]; };
uniform uint uWrites;
void main() {
    uint beyond = data[4];  // the word after the buffer's 4
    for (uint k = 0u; k < uWrites; ++k) data[k] = k;
    data[0] = beyond;
})",
                                                       .files = {},
                                                       .spans = {}});
    for (const unsigned writes : {4u, 5u}) {
        const Buffer data = Buffer::storage(4 * sizeof(std::uint32_t));
        data.bindStorage(0);
        program.set("uWrites", writes);
        program.dispatch(1);
        EXPECT_EQ(data.overrun(), writes > 4) << writes << " writes";
        EXPECT_EQ(data.read<std::uint32_t>(0, 1)[0], poisonWord());
    }
}

// Every buffer holds its first contents from the moment it is made (buffer.h), and a client
// write after a shader's is ordered after it; in poison mode a buffer shaders are to fill holds
// the pattern, NaN or finite (poison.h).
TEST(Buffer, HoldsItsFirstContentsFromTheMomentItIsMade) {
    Context context(ContextOptions{.debug = true});
    const std::vector<std::uint32_t> words = {1u, 2u, 3u, 4u, 5u, 6u};
    Buffer header = Buffer::writableOf(std::span<const std::uint32_t>(words));
    EXPECT_EQ(header.read<std::uint32_t>(0, 6), words);
    const Buffer zeros = Buffer::zeros(64);
    EXPECT_EQ(zeros.read<std::uint32_t>(0, 16), std::vector<std::uint32_t>(16, 0u));
    const Buffer storage = Buffer::storage(64);
    EXPECT_EQ(storage.read<std::uint32_t>(0, 16),
              std::vector<std::uint32_t>(16, poisonMode() ? poisonWord() : 0u));
    // A shader writes word 0; the client's write of word 1 after it keeps the shader's.
    const Program program("write_first", ShaderSource{.text = R"(#version 450
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Data { uint data[]; };
void main() { data[0] = 42u; })",
                                                      .files = {},
                                                      .spans = {}});
    header.bindStorage(0);
    program.dispatch(1);
    const std::uint32_t seven = 7u;
    header.write(4, std::span<const std::uint32_t>(&seven, 1));
    EXPECT_EQ(header.read<std::uint32_t>(0, 3), (std::vector<std::uint32_t>{42u, 7u, 3u}));
    checkErrors("test");
}

// The upload's path: the client writes through the staging buffer's mapping, copyTo() flushes
// and copies; a second mapping waits for the first copy, so the first set arrives whole.
TEST(Buffer, StagedWritesArriveWholeAndInOrder) {
    Context context(ContextOptions{.debug = true});
    StagingBuffer staging;
    Buffer a = Buffer::storage(4096), b = Buffer::storage(4096);
    for (const auto& [target, value] : {std::pair{&a, 11u}, std::pair{&b, 22u}}) {
        const std::span<std::byte> mapped = staging.map(4096);
        const std::vector<std::uint32_t> words(1024, value);
        std::memcpy(mapped.data(), words.data(), 4096);
        staging.copyTo(*target, 0, 4096);
    }
    EXPECT_EQ(a.read<std::uint32_t>(0, 1024), std::vector<std::uint32_t>(1024, 11u));
    EXPECT_EQ(b.read<std::uint32_t>(0, 1024), std::vector<std::uint32_t>(1024, 22u));
    checkErrors("test");
}

TEST(Context, HandlesAreMoveOnlyAndMovingEmptiesTheSource) {
    static_assert(!std::is_copy_constructible_v<Texture>);
    static_assert(std::is_nothrow_move_constructible_v<Handle>);
    Context context(ContextOptions{.debug = true});
    Texture a(4, 4, Format::R32F);
    const unsigned id = a.id();
    ASSERT_NE(id, 0u);
    Texture b = std::move(a);
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is the test
    EXPECT_EQ(b.id(), id);
    const std::array<float, 3> data{1, 2, 3};
    Buffer buffer = Buffer::of(std::span<const float>(data));
    EXPECT_EQ(buffer.size(), sizeof(data));
    TimerQuery query;
    query.begin();
    query.end();
    EXPECT_GE(query.milliseconds(), 0.0);
    checkErrors("test");
}

// A debug context: a call GL refuses fails the next check with the driver's own account of
// it, and the check leaves the log empty for the next pass.
TEST(Context, DebugContextFailsOnAnyGlErrorWithTheDriversMessage) {
    Context context(ContextOptions{.debug = true});
    ASSERT_TRUE(context.isDebug()) << context.description();
    EXPECT_NE(context.description().find("debug"), std::string::npos);
    checkErrors("clean");
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS + 0x1000);  // no such capability: GL_INVALID_ENUM
    try {
        checkErrors("refused");
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'refused'"), std::string::npos) << what;
        EXPECT_NE(what.find("GL_INVALID_ENUM"), std::string::npos) << what;
        // The driver's own words follow, as it chose them: Mesa names the call ("glEnable"),
        // NVIDIA the argument ("<cap> enum is invalid"); neither is asserted.
        const std::size_t log = what.find("the driver's log: error:");
        ASSERT_NE(log, std::string::npos) << what;
        EXPECT_GT(what.size(), log + std::string("the driver's log: error:").size() + 4) << what;
    }
    EXPECT_NO_THROW(checkErrors("after"));
}

TEST(Context, IncompleteFramebufferIsAnErrorNamingIt) {
    Context context;
    Texture a(4, 4, Format::RGBA32F), b(8, 8, Format::RGBA32F);
    try {
        Framebuffer fb("mismatched", {{&a}, {&b}});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("mismatched"), std::string::npos) << e.what();
    }
}

// --require-gpu: a software renderer is refused with the list of what was tried; on a GPU
// machine the context comes up on the GPU.
TEST(Context, RequireGpuRefusesSoftwareRenderers) {
    try {
        Context context(ContextOptions{.requireGpu = true});
        EXPECT_FALSE(context.isSoftware()) << context.description();
    } catch (const core::InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("GPU is required"), std::string::npos) << message;
        EXPECT_NE(message.find("refused"), std::string::npos) << message;
    }
}

// Run by CTest with __EGL_VENDOR_LIBRARY_DIRS pointing at an empty folder (see CMakeLists).
TEST(ContextWithoutEgl, ThrowsInputErrorListingCandidates) {
    if (!std::getenv("TWINRENDER_EXPECT_NO_EGL"))
        GTEST_SKIP() << "needs the EGL vendors hidden; CTest runs it that way";
    try {
        Context context;
        FAIL() << "a context was created: " << context.description();
    } catch (const core::InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("Tried:"), std::string::npos) << message;
        EXPECT_NE(message.find("libegl-mesa0"), std::string::npos) << message;
        EXPECT_NE(message.find("graphics"), std::string::npos) << message;
        std::cout << message << "\n";
    }
}

}  // namespace
}  // namespace twinrender::realtime::gl
