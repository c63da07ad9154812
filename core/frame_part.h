// A frame split into parts by rows of tiles (`render --tiles K/N`, docs/cli.md): part K of N
// holds the rows of the renderer's square tiles whose index r (0 at the top) has
// r % N == K - 1, so that every part takes rows from every height of the frame and the parts
// cost about the same wherever the scene's objects lie (docs/performance.md, "Tiles of one
// frame"). A renderer that draws a part records in it what joining the parts needs
// (PartRecord), and the joined parts (core/part_join.h) are the frame one render gives, bit for
// bit, its times aside.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/image.h"

namespace twinrender::core {

struct FramePart {
    int index = 1;  // K, 1..count
    int count = 1;  // N >= 1; 1: the whole frame

    bool whole() const { return count == 1; }
    // Whether the part holds the row of tiles `row` (0-based from the top).
    bool holdsRow(int row) const { return row % count == index - 1; }
    // The rows of tiles it holds of a frame `height` pixels high cut into tiles `tileSize` high.
    int rowsHeld(int height, int tileSize) const;
};

// A counter that is a mean over the frame's samples (the raymarcher's ao_standard_error): per
// row of tiles the part holds, in order, the sum over that row, and the samples the mean is
// over. One render adds the rows' sums in row order and divides by the samples; the join does
// the same with every part's rows, so the mean is the same double.
struct PartMean {
    std::vector<double> rowSums;
    std::int64_t samples = 0;
};

// What a part of a frame records beside its image (of the whole frame's size, the rows it does
// not hold left zero). Its counters are sums over its tiles, but the `means` and the `shared`
// ones: facts of the whole frame (the raymarcher's emitting_bodies), equal in every part.
struct PartRecord {
    FramePart part;
    int tileSize = 0;  // the side of the renderer's tiles, pixels
    std::map<std::string, PartMean> means;
    std::vector<std::string> shared;
};

// A part's image as its file holds it: the rows of pixels of the rows of tiles it holds, top to
// bottom, so that a part of N is about 1/N of the frame's file to write and to read.
Image heldRows(const Image& whole, const PartRecord& record);
// And back: the image of the whole frame, `height` pixels high, the held rows in place, the
// others zero. Throws InputError naming `where` when `held` has another height than the part's
// rows.
Image placeHeldRows(const Image& held, const PartRecord& record, int height,
                    const std::string& where);

// A render JSON's "tile" object: {"part": K, "of": N, "tile_size", "means": {counter:
// {"row_sums": [...], "samples"}}, "shared": [...]}.
nlohmann::json toJson(const PartRecord& record);
// Reads it back; throws InputError naming `where` and the key when it is not one.
PartRecord partRecordFromJson(const nlohmann::json& j, const std::string& where);

}  // namespace twinrender::core
