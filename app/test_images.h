// Images of a renderer of the user's own, judged as the reference's peers (docs/external.md):
// the image the protocol's command writes for a frame (app/external_renderer.h), and the images
// a user rendered earlier, one per scene and frame, that `run --test-images DIR` takes in the
// external renderer's place. Both are read and checked here alike.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "app/render_job.h"
#include "core/image.h"
#include "core/renderer.h"

namespace twinrender::app {

// The image a renderer of one's own wrote for a frame, read and checked: an EXR (any AOV
// channels) of `width` x `height` pixels with R, G and B, every value finite but +inf in Z.
// Throws core::InputError saying what was wrong; the caller names the renderer and the frame.
core::Image readTestImage(const std::filesystem::path& file, int width, int height);

// A renderer's optional times of a frame, `{"stage": ms, ...}` ("total" the frame's), from the
// JSON file `file`; empty when there is no such file. Throws core::InputError when it is not a
// JSON object.
std::map<std::string, double> readTestTimings(const std::filesystem::path& file);

// Where `run --test-images DIR` finds a frame's image: DIR/<scene>/<frame>.exr, the frame's
// number in four digits (app/sequence_run.h's frameFolder; a still scene's is its frame,
// 0000 unless the scene says). Its times, optional: DIR/<scene>/<frame>.timings.json.
std::filesystem::path testImagePath(const std::filesystem::path& dir, const core::Scene& scene,
                                    std::int64_t frame);

// Reads and checks, before anything renders, the image of every frame of the scene (each frame
// of a sequence's range): throws core::InputError naming the scene, the frame and the path
// expected for a missing image, or what is wrong with one.
void checkTestImages(const std::filesystem::path& dir, const LoadedScene& scene);

// The images of DIR as a renderer: a frame is the scene's image at its frame (testImagePath),
// read and checked. Its frames are the external renderer's ("external", device "images: DIR"),
// so the reports, thresholds and metrics treat both alike.
class TestImages final : public core::Renderer {
  public:
    explicit TestImages(std::filesystem::path dir) : mDir(std::move(dir)) {}
    core::Frame render(const core::RenderInput& input) override;

  private:
    std::filesystem::path mDir;
};

}  // namespace twinrender::app
