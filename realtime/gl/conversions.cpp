#include "realtime/gl/conversions.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>

#include "core/error.h"
#include "realtime/gl/error.h"

namespace twinrender::realtime::gl {

namespace {

constexpr const char* VARIABLE = "TWINRENDER_GL_CONVERSIONS";

// The count in the atomic counter buffer `id`, set back to 0.
std::uint32_t takeCount(unsigned id) {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
    std::uint32_t count = 0;
    glGetNamedBufferSubData(id, 0, sizeof(count), &count);
    glClearNamedBufferSubData(id, GL_R32UI, 0, sizeof(count), GL_RED_INTEGER, GL_UNSIGNED_INT,
                              nullptr);
    return count;
}

void throwIfCounted(std::uint32_t count, std::string_view stage) {
    if (count != 0)
        throw Error(fmt::format(
            "{} converted {} non-finite or out-of-range float{} to integers (shaders/convert.glsl, "
            "{}=count): GLSL leaves the result undefined and GPUs differ",
            stage, count, count == 1 ? "" : "s", VARIABLE));
}

}  // namespace

Conversions parseConversions(std::string_view value) {
    Conversions c;
    bool moded = false;
    std::size_t start = 0;
    while (start <= value.size() && !value.empty()) {
        const std::size_t comma = std::min(value.find(',', start), value.size());
        const std::string_view word = value.substr(start, comma - start);
        if (word == "count" && !c.count) {
            c.count = true;
        } else if ((word == "saturate" || word == "wrap") && !moded) {
            c.mode = word == "saturate" ? ConversionMode::Saturate : ConversionMode::Wrap;
            moded = true;
        } else {
            throw core::InputError(fmt::format(
                "{}='{}': expected saturate, wrap or count, or a mode and count (saturate,count)",
                VARIABLE, value));
        }
        start = comma + 1;
    }
    return c;
}

const Conversions& conversionsMode() {
    static const Conversions mode = [] {
        const char* value = std::getenv(VARIABLE);
        return parseConversions(value ? value : "");
    }();
    return mode;
}

std::vector<std::string> conversionDefines(const Conversions& conversions) {
    std::vector<std::string> defines;
    if (conversions.mode == ConversionMode::Saturate) defines.emplace_back("CONVERSIONS_SATURATE");
    if (conversions.mode == ConversionMode::Wrap) defines.emplace_back("CONVERSIONS_WRAP");
    if (conversions.count) defines.emplace_back("CONVERSIONS_COUNT");
    return defines;
}

ConversionCounter::ConversionCounter() : mBuffer(Buffer::zeros(sizeof(std::uint32_t))) {}

void ConversionCounter::bind() const {
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, CONVERSION_COUNTER_BINDING, mBuffer.id());
}

std::uint32_t ConversionCounter::take() {
    return takeCount(mBuffer.id());
}

void ConversionCounter::check(std::string_view stage) {
    throwIfCounted(take(), stage);
}

void checkConversions(std::string_view kind, std::string_view name) {
    if (!conversionsMode().count) return;
    const std::string stage = fmt::format("{} '{}'", kind, name);
    GLint bound = 0;
    glGetIntegeri_v(GL_ATOMIC_COUNTER_BUFFER_BINDING, CONVERSION_COUNTER_BINDING, &bound);
    if (bound == 0)
        throw Error(
            fmt::format("{}: {}=count but no conversion counter is bound", stage, VARIABLE));
    throwIfCounted(takeCount(static_cast<unsigned>(bound)), stage);
}

}  // namespace twinrender::realtime::gl
