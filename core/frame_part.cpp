#include "core/frame_part.h"

#include <fmt/format.h>

#include "core/error.h"

namespace twinrender::core {

using nlohmann::json;

int FramePart::rowsHeld(int height, int tileSize) const {
    const int rows = (height + tileSize - 1) / tileSize;
    return rows < index ? 0 : (rows - index) / count + 1;
}

int FramePart::heightHeld(int height, int tileSize) const {
    const int rows = (height + tileSize - 1) / tileSize;
    // A held last row of tiles may be cut short by the frame's edge.
    const int cut = holdsRow(rows - 1) ? rows * tileSize - height : 0;
    return rowsHeld(height, tileSize) * tileSize - cut;
}

json toJson(const PartRecord& r) {
    json means = json::object();
    for (const auto& [name, m] : r.means)
        means[name] = {{"row_sums", m.rowSums}, {"samples", m.samples}};
    return {{"part", r.part.index}, {"of", r.part.count}, {"tile_size", r.tileSize},
            {"height", r.height},   {"means", means},     {"maxima", r.maxima},
            {"shared", r.shared}};
}

PartRecord partRecordFromJson(const json& j, const std::string& where) {
    // Types are checked, never converted: a damaged part is bad input naming the key.
    const auto bad = [&](const std::string& key, const char* what) {
        return InputError(fmt::format("{}: \"tile\".{} is {}, not {}", where, key,
                                      j.contains(key) ? j.at(key).dump() : "missing", what));
    };
    if (!j.is_object())
        throw InputError(fmt::format("{}: \"tile\" is {}, not an object", where, j.dump()));
    const auto integer = [&](const char* key, long long least) {
        const auto it = j.find(key);
        if (it == j.end() || !it->is_number_integer() || it->get<long long>() < least ||
            it->get<long long>() > 1 << 20)
            throw bad(key, least == 0 ? "a whole number" : "a positive whole number");
        return static_cast<int>(it->get<long long>());
    };
    PartRecord r;
    r.part = {.index = integer("part", 1), .count = integer("of", 1)};
    if (r.part.index > r.part.count) throw bad("part", "a part number between 1 and \"of\"");
    r.tileSize = integer("tile_size", 1);
    r.height = integer("height", 1);
    if (r.height > 16384) throw bad("height", "a frame's height, 1 to 16384 (camera.height)");
    const auto means = j.find("means");
    if (means == j.end() || !means->is_object()) throw bad("means", "an object");
    for (const auto& [name, m] : means->items()) {
        const std::string key = "means." + name;
        if (!m.is_object() || !m.contains("row_sums") || !m.at("row_sums").is_array() ||
            !m.contains("samples") || !m.at("samples").is_number_integer())
            throw InputError(
                fmt::format("{}: \"tile\".{} is {}, not {{\"row_sums\": [...], "
                            "\"samples\": N}}",
                            where, key, m.dump()));
        PartMean mean;
        for (const json& v : m.at("row_sums")) {
            if (!v.is_number())
                throw InputError(fmt::format("{}: \"tile\".{}.row_sums holds {}, not a number",
                                             where, key, v.dump()));
            mean.rowSums.push_back(v.get<double>());
        }
        mean.samples = m.at("samples").get<std::int64_t>();
        r.means.emplace(name, std::move(mean));
    }
    const auto names = [&](const char* key, std::vector<std::string>& into) {
        const auto list = j.find(key);
        if (list == j.end() || !list->is_array()) throw bad(key, "a list of counters");
        for (const json& v : *list) {
            if (!v.is_string()) throw bad(key, "a list of counters");
            into.push_back(v.get<std::string>());
        }
    };
    names("maxima", r.maxima);
    names("shared", r.shared);
    return r;
}

}  // namespace twinrender::core
