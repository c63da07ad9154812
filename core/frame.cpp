#include "core/frame.h"

#include <limits>

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
    writeImage(frame.image, dir / (name + ".exr"));
    writeImage(frame.display, dir / (name + ".png"));
    nlohmann::json j = extra;
    j["renderer"] = frame.renderer;
    j["device"] = frame.device;
    j["settings"] = frame.settings;
    j["particle_count"] = frame.particleCount;
    j["resolution"] = {frame.image.width(), frame.image.height()};
    j["counters"] = frame.counters;
    j["timings_ms"] = frame.timingsMs;
    writeTextFile(dir / (name + ".json"), j.dump(2) + "\n");
}

}  // namespace twinrender::core
