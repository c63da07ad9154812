// The float-to-integer helpers (shaders/convert.glsl) and their test modes (gl/conversions.h):
// what each mode gives for the inputs GLSL leaves undefined, and that counting counts them.
#include <gtest/gtest.h>

#include <cstdint>
#include <glm/vec4.hpp>
#include <iostream>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "realtime/gl/buffer.h"
#include "realtime/gl/context.h"
#include "realtime/gl/conversions.h"
#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gl/program.h"
#include "realtime/shader_library.h"

namespace twinrender::realtime {
namespace {

constexpr float INF = std::numeric_limits<float>::infinity();
constexpr std::int32_t INT_MIN_ = std::numeric_limits<std::int32_t>::min();
constexpr std::int32_t INT_MAX_ = std::numeric_limits<std::int32_t>::max();
constexpr std::int32_t SATURATED = 1 << 30;  // saturateToInt's bound
constexpr std::uint32_t UINT_MAX_ = 0xFFFFFFFFu;

// GLSL's undefined inputs, then some it defines.
const std::vector<float> INPUTS = {
    std::numeric_limits<float>::quiet_NaN(), INF, -INF, 1e20f, -1e20f, -1.5f, 2.7f, -0.5f, 3e9f};
constexpr std::uint32_t BAD_FOR_INT = 6;   // NaN, +-inf, +-1e20, 3e9 (> INT_MAX)
constexpr std::uint32_t BAD_FOR_UINT = 6;  // NaN, +-inf, +-1e20, -1.5
constexpr std::uint32_t NOT_FINITE = 3;    // NaN, +-inf: saturateToInt counts only those

// Per input: toInt, toUint, clampToInt(x, -5, 5), saturateToInt, toIndex (convert_check.comp).
struct Answer {
    std::int32_t toInt;
    std::uint32_t toUint;
    std::int32_t clamped, saturated;
    std::uint32_t index;
};

std::vector<Answer> convert(const std::vector<std::string>& defines) {
    const gl::Program program("convert_check.comp", composeShader("convert_check.comp", defines));
    const gl::Buffer inputs = gl::Buffer::of(std::span<const float>(INPUTS));
    const gl::Buffer outputs = gl::Buffer::zeros(2 * INPUTS.size() * sizeof(glm::ivec4));
    inputs.bindStorage(0);
    outputs.bindStorage(1);
    program.dispatch(static_cast<unsigned>(INPUTS.size()));
    gl::computeBarrier();
    const std::vector<glm::ivec4> words = outputs.read<glm::ivec4>(0, 2 * INPUTS.size());
    std::vector<Answer> answers;
    for (std::size_t i = 0; i < INPUTS.size(); ++i) {
        const glm::ivec4 a = words[2 * i];
        answers.push_back({a.x, static_cast<std::uint32_t>(a.y), a.z, a.w,
                           static_cast<std::uint32_t>(words[2 * i + 1].x)});
    }
    return answers;
}

// clampToInt, saturateToInt and toIndex answer alike in every mode.
void expectDefinedHelpers(const std::vector<Answer>& a, const char* mode) {
    const std::int32_t clamped[] = {-5, 5, -5, 5, -5, -1, 2, 0, 5};
    const std::int32_t saturated[] = {-SATURATED, SATURATED, -SATURATED, SATURATED, -SATURATED,
                                      -1,         2,         0,          SATURATED};
    const std::uint32_t indices[] = {0, SATURATED, 0, SATURATED, 0, 0, 2, 0, SATURATED};
    for (std::size_t i = 0; i < INPUTS.size(); ++i) {
        EXPECT_EQ(a[i].index, indices[i]) << mode << ": toIndex(" << INPUTS[i] << ")";
        EXPECT_EQ(a[i].clamped, clamped[i]) << mode << ": clampToInt(" << INPUTS[i] << ", -5, 5)";
        EXPECT_EQ(a[i].saturated, saturated[i]) << mode << ": saturateToInt(" << INPUTS[i] << ")";
    }
}

TEST(Conversions, SaturateAnswersAsNvidia) {
    gl::Context context;
    const std::vector<Answer> a = convert({"CONVERSIONS_SATURATE"});
    const std::int32_t ints[] = {0, INT_MAX_, INT_MIN_, INT_MAX_, INT_MIN_, -1, 2, 0, INT_MAX_};
    const std::uint32_t uints[] = {0, UINT_MAX_, 0, UINT_MAX_, 0, 0, 2, 0, 3000000000u};
    for (std::size_t i = 0; i < INPUTS.size(); ++i) {
        EXPECT_EQ(a[i].toInt, ints[i]) << "toInt(" << INPUTS[i] << ")";
        EXPECT_EQ(a[i].toUint, uints[i]) << "toUint(" << INPUTS[i] << ")";
    }
    expectDefinedHelpers(a, "saturate");
}

TEST(Conversions, WrapAnswersAsX86) {
    gl::Context context;
    const std::vector<Answer> a = convert({"CONVERSIONS_WRAP"});
    const std::int32_t ints[] = {INT_MIN_, INT_MIN_, INT_MIN_, INT_MIN_, INT_MIN_,
                                 -1,       2,        0,        INT_MIN_};
    const std::uint32_t uints[] = {UINT_MAX_, UINT_MAX_, UINT_MAX_, UINT_MAX_,  UINT_MAX_,
                                   UINT_MAX_, 2,         0,         3000000000u};
    for (std::size_t i = 0; i < INPUTS.size(); ++i) {
        EXPECT_EQ(a[i].toInt, ints[i]) << "toInt(" << INPUTS[i] << ")";
        EXPECT_EQ(a[i].toUint, uints[i]) << "toUint(" << INPUTS[i] << ")";
    }
    expectDefinedHelpers(a, "wrap");
}

// Without a mode toInt and toUint are the driver's (printed, for the GPU check's log; on
// llvmpipe wrap's, measured with LLVM 15 on AVX2); the defined inputs and the other helpers are
// the same.
TEST(Conversions, NativeDefinesTheRest) {
    gl::Context context;
    const std::vector<Answer> a = convert({});
    const bool llvmpipe = context.renderer().starts_with("llvmpipe");
    const std::vector<Answer> wrap = llvmpipe ? convert({"CONVERSIONS_WRAP"}) : a;
    for (std::size_t i = 0; i < INPUTS.size(); ++i) {
        std::cout << context.renderer() << ": int(" << INPUTS[i] << ") = " << a[i].toInt
                  << ", uint(" << INPUTS[i] << ") = 0x" << std::hex << a[i].toUint << std::dec
                  << "\n";
        EXPECT_EQ(a[i].toInt, wrap[i].toInt) << "int(" << INPUTS[i] << ")";
        EXPECT_EQ(a[i].toUint, wrap[i].toUint) << "uint(" << INPUTS[i] << ")";
    }
    EXPECT_EQ(a[5].toInt, -1);
    EXPECT_EQ(a[6].toInt, 2);
    EXPECT_EQ(a[6].toUint, 2u);
    EXPECT_EQ(a[7].toInt, 0);
    EXPECT_EQ(a[7].toUint, 0u);
    EXPECT_EQ(a[8].toUint, 3000000000u);
    expectDefinedHelpers(a, "native");
}

// Each of the five helpers counts its bad inputs (saturateToInt its non-finite ones), in either
// mode; the check throws naming the stage and the count, and the count starts again from 0.
TEST(Conversions, CountingCountsEachBadInputAndTheCheckNamesTheStage) {
    gl::Context context;
    for (const char* mode : {"CONVERSIONS_SATURATE", "CONVERSIONS_WRAP"}) {
        gl::ConversionCounter counter;
        counter.bind();
        convert({mode, "CONVERSIONS_COUNT"});
        EXPECT_EQ(counter.take(), 3 * BAD_FOR_INT + BAD_FOR_UINT + NOT_FINITE) << mode;
        EXPECT_EQ(counter.take(), 0u);
        convert({mode, "CONVERSIONS_COUNT"});
        try {
            counter.check("pass 'test'");
            ADD_FAILURE() << "no throw";
        } catch (const gl::Error& e) {
            EXPECT_NE(std::string(e.what()).find("pass 'test' converted 27 non-finite"),
                      std::string::npos)
                << e.what();
        }
        EXPECT_NO_THROW(counter.check("pass 'test'"));
        // checkConversions checks the bound counter where the process counts.
        if (gl::conversionsMode().count) {
            convert({mode, "CONVERSIONS_COUNT"});
            EXPECT_THROW(gl::checkConversions("pass", "test"), gl::Error);
        }
    }
}

TEST(Conversions, TheVariableTakesAModeAndCount) {
    EXPECT_EQ(gl::parseConversions("").mode, gl::ConversionMode::Native);
    EXPECT_FALSE(gl::parseConversions("").count);
    EXPECT_EQ(gl::parseConversions("wrap").mode, gl::ConversionMode::Wrap);
    const gl::Conversions both = gl::parseConversions("saturate,count");
    EXPECT_EQ(both.mode, gl::ConversionMode::Saturate);
    EXPECT_TRUE(both.count);
    EXPECT_TRUE(gl::parseConversions("count,wrap").count);
    EXPECT_EQ(gl::conversionDefines(both),
              (std::vector<std::string>{"CONVERSIONS_SATURATE", "CONVERSIONS_COUNT"}));
    for (const char* bad : {"nvidia", "saturate,wrap", "count,count", "saturate,"})
        EXPECT_THROW(gl::parseConversions(bad), core::InputError) << bad;
}

}  // namespace
}  // namespace twinrender::realtime
