// A headless OpenGL 4.5 core context through EGL, with no window and no surface.
// Display candidates, in order: each EGL device that is not Mesa's software device (a real
// GPU), Mesa's software device (llvmpipe), Mesa's surfaceless platform. When none gives a
// context, the constructor throws core::InputError listing every candidate with its EGL error
// and what to install. With requireGpu, software devices and software renderers are refused.
//
// The context is made current on the constructing thread and stays current: one context per
// thread, created by app/ (or a test) and handed to the renderer.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace twinrender::realtime::gl {

struct ContextOptions {
    bool requireGpu = false;  // refuse llvmpipe / softpipe / Mesa's software EGL device
    // A KHR_debug debug context whose driver logs every GL error with what caused it:
    // checkErrors (gl/error.h) then throws on any error message the driver logged as well as
    // on glGetError's codes. The tests run with it (twinrender: TWINRENDER_GL_DEBUG=1).
    bool debug = false;
};

class Context {
  public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;
    Context(Context&&) = delete;
    Context& operator=(Context&&) = delete;

    const std::string& renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    const std::string& vendor() const;    // GL_VENDOR
    const std::string& version() const;   // GL_VERSION
    const std::string& platform() const;  // the EGL candidate that worked, e.g. "EGL device 1"
    bool isSoftware() const;              // a CPU rasteriser (llvmpipe, softpipe, swrast)
    bool isDebug() const;                 // a debug context that logs GL errors (ContextOptions)
    // One line for logs: renderer, GL version and EGL platform.
    std::string description() const;
    // The candidates tried before the one that worked, with why each failed (for logs).
    const std::vector<std::string>& skipped() const;

    // Makes the context current on the calling thread (it already is on the creating one).
    void makeCurrent() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

// GL_RENDERER of the context current on the calling thread.
std::string currentRenderer();

}  // namespace twinrender::realtime::gl
