// A frame split into parts by rows of tiles (`render --tiles K/N`, docs/cli.md): part K of N
// holds the rows of the renderer's square tiles whose index r (0 at the top) has
// r % N == K - 1, so that every part takes rows from every height of the frame and the parts
// cost about the same wherever the scene's objects lie (docs/performance.md, "Tiles of one
// frame"). A part's images hold its rows of pixels alone, top to bottom (about 1/N of the
// frame's memory and file), and the renderer records in it what joining the parts needs
// (PartRecord); the joined parts (core/part_join.h) are the frame one render gives, bit for
// bit, its times aside.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace twinrender::core {

struct FramePart {
    int index = 1;  // K, 1..count
    int count = 1;  // N >= 1; 1: the whole frame

    bool whole() const { return count == 1; }
    // Whether the part holds the row of tiles `row` (0-based from the top).
    bool holdsRow(int row) const { return row % count == index - 1; }
    // The rows of tiles it holds of a frame `height` pixels high cut into tiles `tileSize` high.
    int rowsHeld(int height, int tileSize) const;
    // The rows of pixels it holds of that frame: its images' height.
    int heightHeld(int height, int tileSize) const;
    // The row of its images that holds the frame's row of pixels y (in a row of tiles it
    // holds), and the frame's row that its images' row `row` holds.
    int imageRow(int y, int tileSize) const {
        return y / tileSize / count * tileSize + y % tileSize;
    }
    int frameRow(int row, int tileSize) const {
        return (row / tileSize * count + index - 1) * tileSize + row % tileSize;
    }
};

// A counter that is a mean over the frame's samples (the raymarcher's ao_standard_error): per
// row of tiles the part holds, in order, the sum over that row, and the samples the mean is
// over. One render adds the rows' sums in row order and divides by the samples; the join does
// the same with every part's rows, so the mean is the same double.
struct PartMean {
    std::vector<double> rowSums;
    std::int64_t samples = 0;
};

// What a part of a frame records beside its images. Its counters are sums over its tiles, but
// the `means`, the `maxima` (the largest over the part: the frame's is the largest over the
// parts) and the `shared` ones: facts of the whole frame (the raymarcher's emitting_bodies),
// equal in every part.
struct PartRecord {
    FramePart part;
    int tileSize = 0;  // the side of the renderer's tiles, pixels
    int height = 0;    // the whole frame's, pixels
    std::map<std::string, PartMean> means;
    std::vector<std::string> maxima;
    std::vector<std::string> shared;

    // The part's images' height.
    int heightHeld() const { return part.heightHeld(height, tileSize); }
};

// A render JSON's "tile" object: {"part": K, "of": N, "tile_size", "height", "means": {counter:
// {"row_sums": [...], "samples"}}, "maxima": [...], "shared": [...]}.
nlohmann::json toJson(const PartRecord& record);
// Reads it back; throws InputError naming `where` and the key when it is not one.
PartRecord partRecordFromJson(const nlohmann::json& j, const std::string& where);

}  // namespace twinrender::core
