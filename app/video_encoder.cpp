#include "app/video_encoder.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "core/write_roots.h"
#include "report/sequence_video.h"

extern char** environ;

namespace twinrender::app {

namespace fs = std::filesystem;

namespace {

std::string ffmpegCommand() {
    const char* env = std::getenv("TWINRENDER_FFMPEG");
    return env && *env ? env : "ffmpeg";
}

// Runs argv with stdin from `in` (-1: /dev/null) and stdout and stderr into `log`; returns the
// child's id. Throws std::runtime_error when it cannot be started.
pid_t spawn(const std::vector<std::string>& args, int in, const fs::path& log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (in >= 0)
        posix_spawn_file_actions_adddup2(&actions, in, STDIN_FILENO);
    else
        posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0)
        throw std::runtime_error(fmt::format("cannot run {}: {}", args.front(), std::strerror(rc)));
    return pid;
}

int waitFor(pid_t pid) {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// The log's text, its last `tail` characters.
std::string readLog(const fs::path& log, std::size_t tail = 2000) {
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    return text.size() > tail ? "..." + text.substr(text.size() - tail) : text;
}

fs::path temporary(const fs::path& file) {
    return file.parent_path() / ("." + file.filename().string() + ".partial");
}

}  // namespace

std::string requireFfmpeg() {
    const std::string ffmpeg = ffmpegCommand();
    const fs::path log =
        fs::temp_directory_path() / fmt::format("twinrender_ffmpeg_{}.txt", getpid());
    int rc = -1;
    try {
        rc = waitFor(spawn({ffmpeg, "-hide_banner", "-encoders"}, -1, log));
    } catch (const std::runtime_error&) {
    }
    const std::string encoders = rc == 0 ? readLog(log, std::string::npos) : "";
    std::error_code ec;
    fs::remove(log, ec);
    const char* install =
        "a sequence's video needs Debian's ffmpeg (apt-get install ffmpeg; scripts/setup "
        "installs it), or TWINRENDER_FFMPEG naming an ffmpeg with libx264 and libvpx-vp9";
    if (rc != 0) throw core::InputError(fmt::format("{} cannot be run; {}", ffmpeg, install));
    for (const char* encoder : {"libx264", "libvpx-vp9"})
        if (encoders.find(encoder) == std::string::npos)
            throw core::InputError(
                fmt::format("{} has no {} encoder; {}", ffmpeg, encoder, install));
    return ffmpeg;
}

VideoEncoder::VideoEncoder(fs::path mp4, fs::path webm, double fps)
    : mMp4(std::move(mp4)), mWebm(std::move(webm)), mFps(fps) {
    mLog = mMp4.parent_path() / ".ffmpeg_log.txt";
}

VideoEncoder::~VideoEncoder() {
    if (mPipe || mPid > 0) abandon();
}

void VideoEncoder::abandon() {
    if (mPipe) std::fclose(mPipe);
    mPipe = nullptr;
    if (mPid > 0) {
        kill(mPid, SIGTERM);
        waitFor(mPid);
        mPid = -1;
    }
    std::error_code ec;
    for (const fs::path& f : {temporary(mMp4), temporary(mWebm), mLog}) fs::remove(f, ec);
}

void VideoEncoder::add(const core::Image& frame) {
    if (!mPipe) {
        mWidth = frame.width();
        mHeight = frame.height();
        if (mWidth % 2 || mHeight % 2)
            throw std::invalid_argument(
                fmt::format("video frames of {}x{}: yuv420p needs even sizes", mWidth, mHeight));
        core::makeFolders(mMp4.parent_path());
        core::makeFolders(mWebm.parent_path());
        int fds[2];
        if (pipe(fds) != 0) throw std::runtime_error("cannot open a pipe to ffmpeg");
        // The writing end stays with this process only.
        fcntl(fds[1], F_SETFD, FD_CLOEXEC);
        const std::string size = fmt::format("{}x{}", mWidth, mHeight),
                          rate = fmt::format("{}", mFps);
        const std::vector<std::string> args = {
            ffmpegCommand(), "-hide_banner", "-loglevel", "error", "-y", "-f", "rawvideo",
            "-pix_fmt", "rgb24", "-s", size, "-framerate", rate, "-i", "-",
            // H.264 in MP4: yuv420p (what browsers decode), the index first (fast start).
            "-map", "0", "-c:v", "libx264", "-preset", "medium", "-crf", "18", "-pix_fmt",
            "yuv420p", "-movflags", "+faststart", "-f", "mp4", temporary(mMp4).string(),
            // VP9 in WebM, constant quality.
            "-map", "0", "-c:v", "libvpx-vp9", "-crf", "30", "-b:v", "0", "-deadline", "good",
            "-cpu-used", "4", "-row-mt", "1", "-pix_fmt", "yuv420p", "-f", "webm",
            temporary(mWebm).string()};
        try {
            mPid = spawn(args, fds[0], mLog);
        } catch (...) {
            close(fds[0]);
            close(fds[1]);
            throw;
        }
        close(fds[0]);
        mPipe = fdopen(fds[1], "wb");
        // ffmpeg leaving early closes the pipe: a write then fails instead of ending the
        // process, and add() or finish() reports ffmpeg's message.
        std::signal(SIGPIPE, SIG_IGN);
    }
    if (frame.width() != mWidth || frame.height() != mHeight)
        throw std::invalid_argument(fmt::format("a video frame of {}x{} after frames of {}x{}",
                                                frame.width(), frame.height(), mWidth, mHeight));
    const std::vector<std::uint8_t> bytes = report::rgb8(frame);
    if (std::fwrite(bytes.data(), 1, bytes.size(), mPipe) != bytes.size()) {
        const std::string log = readLog(mLog);
        abandon();
        throw std::runtime_error(fmt::format("ffmpeg stopped reading frames: {}", log));
    }
    ++mFrames;
}

int VideoEncoder::finish() {
    if (!mPipe) throw std::logic_error("VideoEncoder::finish without frames");
    std::fclose(mPipe);
    mPipe = nullptr;
    const int rc = waitFor(mPid);
    mPid = -1;
    if (rc != 0) {
        const std::string log = readLog(mLog);
        abandon();
        throw std::runtime_error(fmt::format("ffmpeg failed (exit status {}): {}", rc, log));
    }
    fs::rename(temporary(mMp4), mMp4);
    fs::rename(temporary(mWebm), mWebm);
    std::error_code ec;
    fs::remove(mLog, ec);
    return mFrames;
}

}  // namespace twinrender::app
