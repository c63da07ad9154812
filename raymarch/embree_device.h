// RAII ownership of an Embree device. Embree reports errors through a callback; this class
// records the last one so that callers turn it into an exception with their context.
#pragma once

#include <embree3/rtcore.h>

#include <string>

namespace twinrender::raymarch {

class EmbreeDevice {
  public:
    // `config` is Embree's device configuration string ("" for the defaults).
    explicit EmbreeDevice(const char* config = "");
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;

    RTCDevice get() const { return mDevice; }
    // Throws std::runtime_error("<what>: <Embree's message>") when Embree reported an error
    // since the last check.
    void check(const char* what) const;

  private:
    static void onError(void* self, RTCError code, const char* message);

    RTCDevice mDevice = nullptr;
    mutable std::string mLastError;
};

}  // namespace twinrender::raymarch
