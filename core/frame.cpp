#include "core/frame.h"

#include <fmt/format.h>

#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/image_io.h"
#include "core/shading.h"

namespace twinrender::core {

Image aov::makeImage(int width, int height) {
    Image img(width, height, channelNames());
    img.fillChannel(img.channelIndex("Z"), std::numeric_limits<float>::infinity());
    img.fillChannel(img.channelIndex("id"), -1.0f);
    return img;
}

Image tonemappedBeauty(const Image& aovImage, float exposure) {
    Image out(aovImage.width(), aovImage.height(), {"R", "G", "B"});
    const int r = aovImage.requireChannel("R"), g = aovImage.requireChannel("G"),
              b = aovImage.requireChannel("B");
    for (std::size_t p = 0; p < aovImage.pixelCount(); ++p) {
        const glm::vec3 c =
            tonemap({aovImage.at(p, r), aovImage.at(p, g), aovImage.at(p, b)}, exposure);
        for (int k = 0; k < 3; ++k) out.at(p, k) = c[k];
    }
    return out;
}

void writeFrame(const Frame& frame, const std::filesystem::path& dir, const nlohmann::json& extra) {
    const std::string& name = frame.renderer;
    // A part that holds no row of tiles (more parts than rows) has no image to write.
    if (frame.image.height() > 0) writeImage(frame.image, dir / (name + ".exr"));
    // A part's rows alone make no picture; the joined frame has one.
    if (!frame.part) writeImage(frame.display, dir / (name + ".png"));
    nlohmann::json j = extra;
    j["renderer"] = frame.renderer;
    j["device"] = frame.device;
    j["settings"] = frame.settings;
    j["particle_count"] = frame.particleCount;
    j["resolution"] = {frame.image.width(), frame.part ? frame.part->height : frame.image.height()};
    j["counters"] = frame.counters;
    j["timings_ms"] = frame.timingsMs;
    if (frame.part) j["tile"] = toJson(*frame.part);
    writeTextFile(dir / (name + ".json"), j.dump(2) + "\n");
}

Frame readFrame(const std::filesystem::path& dir, const std::string& renderer,
                nlohmann::json* json) {
    const std::filesystem::path meta = dir / (renderer + ".json");
    std::ifstream in(meta);
    if (!in) throw InputError(fmt::format("{}: cannot be read", meta.string()));
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.is_object())
        throw InputError(fmt::format("{}: not a JSON object", meta.string()));
    Frame f;
    f.renderer = renderer;
    f.device = j.value("device", "");
    f.settings = j.value("settings", nlohmann::json());
    // Bound to locals: items() of a temporary would dangle.
    const nlohmann::json timings = j.value("timings_ms", nlohmann::json::object());
    const nlohmann::json counters = j.value("counters", nlohmann::json::object());
    for (const auto& [k, v] : timings.items())
        if (v.is_number()) f.timingsMs[k] = v.get<double>();
    for (const auto& [k, v] : counters.items())
        if (v.is_number()) f.counters[k] = v.get<double>();
    f.particleCount = j.value("particle_count", std::size_t{0});
    if (j.contains("tile")) f.part = partRecordFromJson(j.at("tile"), meta.string());
    const std::filesystem::path exr = dir / (renderer + ".exr");
    if (f.part && f.part->heightHeld() == 0) {
        // A part that holds no row wrote no image: one of the frame's width and no row.
        const nlohmann::json::json_pointer width("/resolution/0");
        if (!j.contains(width) || !j.at(width).is_number_integer() || j.at(width).get<int>() < 1)
            throw InputError(
                fmt::format("{}: \"resolution\" is not [width, height]", meta.string()));
        f.image = Image(j.at(width).get<int>(), 0, {});
    } else {
        if (!std::filesystem::exists(exr))
            throw InputError(fmt::format("{}: missing (was the render cut short?)", exr.string()));
        f.image = readImage(exr);
    }
    if (f.part && f.image.height() != f.part->heightHeld())
        throw InputError(fmt::format(
            "{}: {} rows of pixels; part {}/{} of a frame {} pixels high in tiles of {} holds {}",
            exr.string(), f.image.height(), f.part->part.index, f.part->part.count, f.part->height,
            f.part->tileSize, f.part->heightHeld()));
    if (json) *json = j;
    return f;
}

}  // namespace twinrender::core
