// The named per-particle values of text and PLY particle files: CSV columns and PLY vertex
// properties x y z h and optional m rho u v temperature body, and their collection into
// ParticleFileData.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "core/particle_file.h"

namespace twinrender::core::particle_io {

constexpr std::string_view COLUMNS_HINT = "x, y, z, h (optional: m, rho, u, v, temperature, body)";

// The attributes a PLY or CSV file may give per particle, by column / property name.
enum class Field { X, Y, Z, H, MASS, DENSITY, U, V, TEMPERATURE, BODY, COUNT };
constexpr std::size_t FIELD_COUNT = static_cast<std::size_t>(Field::COUNT);
constexpr std::array<std::string_view, FIELD_COUNT> FIELD_NAMES = {
    "x", "y", "z", "h", "m", "rho", "u", "v", "temperature", "body"};

// The field named `name` (a column or property name), if any.
std::optional<Field> fieldByName(std::string_view name);

// Parses the whole of `text` as a number; accepts a leading '+', nan and inf (which the
// validation then rejects with the particle's location, a clearer message than "not a number").
std::optional<double> parseNumber(std::string_view text);

// Collects per-particle field values of a PLY or CSV file into ParticleFileData.
class FieldSink {
  public:
    // `present[f]` says which fields the file has; x, y, z, h and a u/v pair are checked by the
    // caller, which knows how to name the header location.
    explicit FieldSink(const std::array<bool, FIELD_COUNT>& present) : mPresent(present) {}

    bool has(Field f) const { return mPresent[static_cast<std::size_t>(f)]; }

    // Appends one particle. `where` names it for an error ("<path>:12: particle 10").
    void add(const std::array<double, FIELD_COUNT>& v, const std::function<std::string()>& where);

    ParticleFileData take() { return std::move(mData); }

  private:
    std::array<bool, FIELD_COUNT> mPresent;
    ParticleFileData mData;
};

}  // namespace twinrender::core::particle_io
