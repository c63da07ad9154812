#include "realtime/gl/context.h"

#include <dlfcn.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <optional>

#include "core/device_name.h"
#include "core/error.h"
#include "realtime/gl/conversions.h"

namespace twinrender::realtime::gl {

namespace {

std::string eglErrorName(EGLint code) {
    switch (code) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_CURRENT_SURFACE:
            return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_NATIVE_PIXMAP:
            return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW:
            return "EGL_BAD_NATIVE_WINDOW";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE:
            return "EGL_BAD_SURFACE";
        case EGL_CONTEXT_LOST:
            return "EGL_CONTEXT_LOST";
        default:
            return "unknown EGL error";
    }
}

// "call failed: EGL_BAD_MATCH (0x3009)"
std::string eglFailure(const char* call) {
    const EGLint code = eglGetError();
    return fmt::format("{} failed: {} (0x{:04X})", call, eglErrorName(code), code);
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

std::string glString(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "";
}

// On a debug context: the driver logs the errors (and undefined behaviour) it sees, with their
// cause, synchronously in the call that made them, for checkErrors to read; nothing else, so
// performance notes and the like never fill the log. No callback: the log is the context's
// own, where a callback would need state outside it. False when the context is no debug one.
bool enableDebugLog() {
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    if (!(flags & GL_CONTEXT_FLAG_DEBUG_BIT)) return false;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_FALSE);
    for (GLenum type : {GL_DEBUG_TYPE_ERROR, GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR})
        glDebugMessageControl(GL_DONT_CARE, type, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    return true;
}

struct Candidate {
    std::string name;
    EGLenum platform = 0;
    void* nativeDisplay = nullptr;
    bool software = false;
};

}  // namespace

struct Context::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    GLuint vertexArray = 0;
    std::string renderer, vendor, version, platform;
    bool software = false;
    bool debug = false;
    std::vector<std::string> skipped;
    // TWINRENDER_GL_CONVERSIONS=count: the shaders' conversion counter (gl/conversions.h).
    std::optional<ConversionCounter> conversions;
};

Context::Context(const ContextOptions& options) : mImpl(std::make_unique<Impl>()) {
    const bool countConversions = conversionsMode().count;  // a bad value: before any EGL work
    // libepoxy aborts the process when it cannot load libEGL: find it first so that a
    // machine without EGL gets a message instead.
    if (void* lib = dlopen("libEGL.so.1", RTLD_LAZY | RTLD_LOCAL)) {
        dlclose(lib);
    } else {
        throw core::InputError(fmt::format(
            "no usable OpenGL: libEGL.so.1 cannot be loaded ({}); install the EGL loader "
            "(Debian: apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri)",
            dlerror()));
    }

    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    std::vector<Candidate> candidates;
    std::vector<std::string> failures;
    const bool platformBase = hasExtension(clientExtensions, "EGL_EXT_platform_base");
    if (!platformBase) {
        if (!clientExtensions || !*clientExtensions)
            failures.push_back(
                "EGL loader: no EGL implementation found (libglvnd has no vendor library: "
                "no client extensions at all)");
        else
            failures.push_back(fmt::format(
                "EGL loader: no EGL_EXT_platform_base (client extensions: {})", clientExtensions));
    }
    if (platformBase && hasExtension(clientExtensions, "EGL_EXT_device_enumeration") &&
        hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        EGLint count = 0;
        std::vector<EGLDeviceEXT> devices;
        if (eglQueryDevicesEXT(0, nullptr, &count) && count > 0) {
            devices.resize(count);
            eglQueryDevicesEXT(count, devices.data(), &count);
            devices.resize(count);
        } else {
            failures.push_back(count == 0 ? std::string("EGL devices: none found (no EGL vendor "
                                                        "library provides a device)")
                                          : "EGL devices: " + eglFailure("eglQueryDevicesEXT"));
        }
        std::vector<Candidate> hardware, software;
        for (std::size_t i = 0; i < devices.size(); ++i) {
            const char* ext = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
            Candidate c;
            c.platform = EGL_PLATFORM_DEVICE_EXT;
            c.nativeDisplay = devices[i];
            c.software = hasExtension(ext, "EGL_MESA_device_software");
            std::string detail = c.software ? "Mesa software device" : "";
            if (hasExtension(ext, "EGL_EXT_device_drm")) {
                if (const char* file = eglQueryDeviceStringEXT(devices[i], EGL_DRM_DEVICE_FILE_EXT))
                    detail = file;
            }
            c.name = fmt::format("EGL device {}{}", i, detail.empty() ? "" : " (" + detail + ")");
            (c.software ? software : hardware).push_back(std::move(c));
        }
        candidates.insert(candidates.end(), hardware.begin(), hardware.end());
        candidates.insert(candidates.end(), software.begin(), software.end());
    } else if (platformBase) {
        failures.push_back(
            "EGL devices: the EGL client lacks EGL_EXT_device_enumeration / "
            "EGL_EXT_platform_device");
    }
    if (platformBase && hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        // Mesa picks the driver itself; the renderer string says whether it is software.
        candidates.push_back({"EGL surfaceless platform (Mesa)", EGL_PLATFORM_SURFACELESS_MESA,
                              EGL_DEFAULT_DISPLAY, false});
    } else if (platformBase) {
        failures.push_back(
            "EGL surfaceless platform: the EGL client lacks "
            "EGL_MESA_platform_surfaceless (Mesa's EGL, libegl-mesa0, provides it)");
    }

    for (const Candidate& c : candidates) {
        if (options.requireGpu && c.software) {
            failures.push_back(c.name + ": refused, a software device and a GPU is required");
            continue;
        }
        // A failed display is left initialised: EGL displays are per-process singletons and
        // terminating one could pull it from under another context of this process.
        auto fail = [&](std::string why) { failures.push_back(c.name + ": " + std::move(why)); };
        EGLDisplay display = eglGetPlatformDisplayEXT(c.platform, c.nativeDisplay, nullptr);
        if (display == EGL_NO_DISPLAY) {
            fail(eglFailure("eglGetPlatformDisplay"));
            continue;
        }
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) {
            fail(eglFailure("eglInitialize"));
            continue;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) {
            fail(eglFailure("eglBindAPI(EGL_OPENGL_API)"));
            continue;
        }
        const char* displayExtensions = eglQueryString(display, EGL_EXTENSIONS);
        if (!hasExtension(displayExtensions, "EGL_KHR_surfaceless_context")) {
            fail("no EGL_KHR_surfaceless_context (a context without a surface is needed)");
            continue;
        }
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!hasExtension(displayExtensions, "EGL_KHR_no_config_context")) {
            const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint configCount = 0;
            if (!eglChooseConfig(display, configAttributes, &config, 1, &configCount) ||
                configCount == 0) {
                fail(configCount == 0 ? std::string("no EGL config renders OpenGL")
                                      : eglFailure("eglChooseConfig"));
                continue;
            }
        }
        const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                            4,
                                            EGL_CONTEXT_MINOR_VERSION,
                                            5,
                                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                            EGL_CONTEXT_FLAGS_KHR,
                                            options.debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
                                            EGL_NONE};
        EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
        if (context == EGL_NO_CONTEXT) {
            fail(eglFailure(options.debug ? "eglCreateContext(OpenGL 4.5 core, debug)"
                                          : "eglCreateContext(OpenGL 4.5 core)"));
            continue;
        }
        if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            fail(eglFailure("eglMakeCurrent"));
            eglDestroyContext(display, context);
            continue;
        }
        const std::string renderer = glString(GL_RENDERER);
        const bool software = c.software || core::isSoftwareRasteriser(renderer);
        if (options.requireGpu && software) {
            fail(fmt::format("refused, renderer '{}' is software and a GPU is required", renderer));
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, context);
            continue;
        }
        mImpl->display = display;
        mImpl->context = context;
        mImpl->renderer = renderer;
        mImpl->vendor = glString(GL_VENDOR);
        mImpl->version = glString(GL_VERSION);
        mImpl->platform = c.name;
        mImpl->software = software;
        mImpl->skipped = failures;
        if (options.debug) mImpl->debug = enableDebugLog();
        // The core profile draws only with a vertex array bound; every draw here pulls its
        // data from buffers, so one empty array serves all.
        glCreateVertexArrays(1, &mImpl->vertexArray);
        glBindVertexArray(mImpl->vertexArray);
        // Counting conversions: one counter bound for every program the context runs.
        if (countConversions) mImpl->conversions.emplace().bind();
        return;
    }

    std::string message = fmt::format("no usable OpenGL 4.5 core context{}. Tried:",
                                      options.requireGpu ? " on a GPU (a GPU is required)" : "");
    if (failures.empty()) message += "\n  (no EGL display candidate at all)";
    for (const auto& f : failures) message += "\n  - " + f;
    for (const char* variable : {"__EGL_VENDOR_LIBRARY_DIRS", "__EGL_VENDOR_LIBRARY_FILENAMES"})
        if (const char* value = std::getenv(variable))
            message += fmt::format("\nNote: {} is set to '{}'.", variable, value);
    message +=
        "\nTo render on the CPU, install Mesa's EGL and DRI drivers (Debian: apt-get install "
        "libegl1 libegl-mesa0 libgl1-mesa-dri). On an NVIDIA GPU, install the driver's EGL "
        "vendor file (10_nvidia.json in /usr/share/glvnd/egl_vendor.d/, from the driver "
        "package) and, in a container, enable the 'graphics' driver capability "
        "(NVIDIA_DRIVER_CAPABILITIES=graphics,compute,utility).";
    throw core::InputError(message);
}

Context::~Context() {
    if (mImpl->context != EGL_NO_CONTEXT) {
        makeCurrent();
        glDeleteVertexArrays(1, &mImpl->vertexArray);
        mImpl->conversions.reset();
        eglMakeCurrent(mImpl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(mImpl->display, mImpl->context);
    }
}

const std::string& Context::renderer() const {
    return mImpl->renderer;
}
const std::string& Context::vendor() const {
    return mImpl->vendor;
}
const std::string& Context::version() const {
    return mImpl->version;
}
const std::string& Context::platform() const {
    return mImpl->platform;
}
bool Context::isSoftware() const {
    return mImpl->software;
}
bool Context::isDebug() const {
    return mImpl->debug;
}
const std::vector<std::string>& Context::skipped() const {
    return mImpl->skipped;
}

std::string Context::description() const {
    return fmt::format("{} (OpenGL {}, {}{}{})", mImpl->renderer, mImpl->version, mImpl->platform,
                       mImpl->software ? ", software" : "", mImpl->debug ? ", debug context" : "");
}

void Context::makeCurrent() const {
    if (eglGetCurrentContext() == mImpl->context) return;
    if (!eglMakeCurrent(mImpl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, mImpl->context))
        throw std::runtime_error(eglFailure("eglMakeCurrent"));
}

std::string currentRenderer() {
    return glString(GL_RENDERER);
}

}  // namespace twinrender::realtime::gl
