// The side-by-side video of a sequence encoded with Debian's ffmpeg: MP4 (H.264, yuv420p,
// fast start, for every browser) and WebM (VP9), from 8-bit RGB frames handed over a pipe, so
// no frame images are written. Both files are written under temporary names and renamed when
// ffmpeg has finished; an encoder destroyed before finish() removes them.
#pragma once

#include <sys/types.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "core/image.h"

namespace twinrender::app {

// The ffmpeg the encoder runs: $TWINRENDER_FFMPEG, else `ffmpeg` on the PATH. Throws
// core::InputError saying what to install when it cannot be run or lacks an encoder (libx264,
// libvpx-vp9): a sequence is bad environment before any rendering, not after it.
std::string requireFfmpeg();

class VideoEncoder {
  public:
    // `mp4` and `webm`: the files to write; `fps`: frames per second, > 0.
    VideoEncoder(std::filesystem::path mp4, std::filesystem::path webm, double fps);
    ~VideoEncoder();
    VideoEncoder(const VideoEncoder&) = delete;
    VideoEncoder& operator=(const VideoEncoder&) = delete;

    // Appends a frame (channels R, G, B in [0, 1]); every frame has the first one's size, even.
    // The first frame starts ffmpeg.
    void add(const core::Image& frame);
    // Waits for ffmpeg and renames the files into place; throws std::runtime_error with
    // ffmpeg's message when it failed. Returns the number of frames encoded.
    int finish();

  private:
    void abandon();

    std::filesystem::path mMp4, mWebm, mLog;
    double mFps;
    int mWidth = 0, mHeight = 0, mFrames = 0;
    pid_t mPid = -1;
    std::FILE* mPipe = nullptr;
};

}  // namespace twinrender::app
