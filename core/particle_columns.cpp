#include "core/particle_columns.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "core/error.h"

namespace twinrender::core::particle_io {

std::optional<Field> fieldByName(std::string_view name) {
    for (std::size_t f = 0; f < FIELD_COUNT; ++f)
        if (FIELD_NAMES[f] == name) return static_cast<Field>(f);
    return std::nullopt;
}

std::optional<double> parseNumber(std::string_view text) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    if (text.empty()) return std::nullopt;
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

void FieldSink::add(const std::array<double, FIELD_COUNT>& v,
                    const std::function<std::string()>& where) {
    auto at = [&](Field f) { return v[static_cast<std::size_t>(f)]; };
    mData.position.emplace_back(at(Field::X), at(Field::Y), at(Field::Z));
    mData.h.push_back(at(Field::H));
    if (has(Field::MASS)) mData.mass.push_back(at(Field::MASS));
    if (has(Field::DENSITY)) mData.density.push_back(at(Field::DENSITY));
    if (has(Field::U)) mData.uv.emplace_back(at(Field::U), at(Field::V));
    if (has(Field::TEMPERATURE)) mData.temperature.push_back(at(Field::TEMPERATURE));
    if (has(Field::BODY)) {
        const double b = at(Field::BODY);
        // 2^62: far beyond any body count, and exactly convertible to int64.
        if (!std::isfinite(b) || b != std::floor(b) || std::abs(b) > 0x1p62)
            throw InputError(
                fmt::format("{} has body = {}; write the body as an integer index", where(), b));
        mData.body.push_back(static_cast<std::int64_t>(b));
    }
}

}  // namespace twinrender::core::particle_io
