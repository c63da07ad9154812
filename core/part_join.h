// Joins the parts of one frame (core/frame_part.h) into the frame one render gives: each
// part's rows of tiles, its counters as one render counts them, its times summed.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/frame.h"

namespace twinrender::core {

class PartJoin {
  public:
    // Adds one part, read from `where` (which the errors name), in any order; only its rows are
    // kept. Throws InputError when it is not a part, is a part number added before, or does
    // not fit the parts added before: another split, tile size, image size or channels,
    // renderer, settings, particle count, counters, or another value of a shared counter.
    void add(Frame part, const std::string& where);

    // The whole frame: every part's rows; the counters summed over the parts, the means
    // computed from every row's sum in row order, the maxima the largest of the parts', the
    // shared ones as every part has them; each
    // stage's time summed over the parts (their build stages too: the time the parts took
    // together); the device the parts' devices, each once, in part order; the display image
    // the beauty tonemapped with `exposure`, as the renderer writes it. Throws InputError
    // naming the first part that is missing.
    Frame frame(float exposure);

    // Each part's number, device and timings_ms, in part order: for the joined frame's JSON.
    nlohmann::json parts() const;

  private:
    struct Added {
        PartRecord record;
        std::string where;
        std::string device;
        std::map<std::string, double> timingsMs;
    };
    void check(const Frame& part, const std::string& where) const;
    void copyRows(const Frame& part);

    Frame mFrame;    // the first part's facts, the rows added so far, the counters' sums
    int mWidth = 0;  // the frame's, pixels (a part that holds no row has no image of it)
    std::map<int, Added> mParts;  // by part number
};

}  // namespace twinrender::core
