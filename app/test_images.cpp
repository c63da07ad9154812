#include "app/test_images.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app/sequence_run.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/image_io.h"
#include "core/sequence.h"

namespace twinrender::app {

namespace fs = std::filesystem;

namespace {

// NaN or an infinity in a channel (+inf in Z is the background's depth): the first such pixel.
std::string firstNonFinite(const core::Image& image) {
    for (int c = 0; c < image.channelCount(); ++c) {
        const bool depth = image.channelNames()[c] == "Z";
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                const float v = image.at(x, y, c);
                if (std::isnan(v) || (std::isinf(v) && !(depth && v > 0)))
                    return fmt::format("{} at pixel ({}, {}) of channel {}", v, x, y,
                                       image.channelNames()[c]);
            }
    }
    return {};
}

// The frames a scene is measured at: each of a sequence's range, else the scene's own.
std::vector<std::int64_t> measuredFrames(const core::Scene& scene) {
    if (scene.sequence) return core::sequenceFrames(scene);
    return {scene.frame};
}

}  // namespace

core::Image readTestImage(const fs::path& file, int width, int height) {
    core::Image image = core::readImage(file);
    if (image.width() != width || image.height() != height)
        throw core::InputError(fmt::format("its image is {}x{} pixels; the camera's is {}x{}",
                                           image.width(), image.height(), width, height));
    for (const char* c : {"R", "G", "B"})
        if (!image.hasChannel(c))
            throw core::InputError(
                fmt::format("its image has no channel \"{}\" (the linear beauty is R, G, B)", c));
    if (const std::string bad = firstNonFinite(image); !bad.empty())
        throw core::InputError("its image holds " + bad +
                               "; every channel must be finite (Z may be +inf where nothing is "
                               "hit)");
    return image;
}

std::map<std::string, double> readTestTimings(const fs::path& file) {
    std::map<std::string, double> timings;
    std::ifstream in(file);
    if (!in) return timings;
    const nlohmann::json t = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (!t.is_object())
        throw core::InputError(
            fmt::format("{} is not a JSON object of stage times in ms", file.filename().string()));
    for (const auto& [stage, ms] : t.items())
        if (ms.is_number()) timings[stage] = ms.get<double>();
    return timings;
}

fs::path testImagePath(const fs::path& dir, const core::Scene& scene, std::int64_t frame) {
    return dir / scene.name / (frameFolder(frame) + ".exr");
}

void checkTestImages(const fs::path& dir, const LoadedScene& s) {
    for (const std::int64_t frame : measuredFrames(s.scene)) {
        const fs::path file = testImagePath(dir, s.scene, frame);
        const std::string where = fmt::format("test images: scene {} ({}), frame {}", s.scene.name,
                                              s.scene.file.string(), frame);
        if (!fs::is_regular_file(file))
            throw core::InputError(fmt::format(
                "{}: no image at {} (run --test-images DIR takes one EXR per scene and frame, "
                "DIR/<scene>/<frame>.exr, the frame in four digits)",
                where, file.string()));
        try {
            readTestImage(file, s.scene.camera.width, s.scene.camera.height);
            readTestTimings(fs::path(file).replace_extension(".timings.json"));
        } catch (const core::InputError& e) {
            throw core::InputError(fmt::format("{}: {}: {}", where, file.string(), e.what()));
        }
    }
}

core::Frame TestImages::render(const core::RenderInput& in) {
    core::requireWholeFrame(in, "test-images");
    const fs::path file = testImagePath(mDir, in.scene, in.scene.frame);
    core::Frame frame;
    try {
        frame.image = readTestImage(file, in.scene.camera.width, in.scene.camera.height);
        frame.timingsMs = readTestTimings(fs::path(file).replace_extension(".timings.json"));
    } catch (const core::InputError& e) {
        throw core::InputError(fmt::format("test images: frame {} of {}: {}: {}", in.scene.frame,
                                           in.scene.name, file.string(), e.what()));
    }
    frame.display =
        core::tonemappedBeauty(frame.image, static_cast<float>(in.scene.camera.exposure));
    frame.renderer = "external";
    frame.device = "images: " + mDir.string();
    frame.particleCount = in.particles.particles.size();
    frame.settings = {{"external.images", file.string()}};
    return frame;
}

}  // namespace twinrender::app
