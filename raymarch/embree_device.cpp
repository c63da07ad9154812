#include "raymarch/embree_device.h"

#include <fmt/format.h>

#include <stdexcept>

namespace twinrender::raymarch {

EmbreeDevice::EmbreeDevice(const char* config) {
    mDevice = rtcNewDevice(config);
    if (!mDevice)
        throw std::runtime_error(fmt::format("cannot create the Embree device (error {})",
                                             static_cast<int>(rtcGetDeviceError(nullptr))));
    rtcSetDeviceErrorFunction(mDevice, &EmbreeDevice::onError, this);
}

EmbreeDevice::~EmbreeDevice() {
    if (mDevice) rtcReleaseDevice(mDevice);
}

void EmbreeDevice::onError(void* self, RTCError code, const char* message) {
    static_cast<EmbreeDevice*>(self)->mLastError =
        fmt::format("Embree error {}: {}", static_cast<int>(code), message ? message : "");
}

void EmbreeDevice::check(const char* what) const {
    if (!mLastError.empty()) {
        std::string msg = fmt::format("{}: {}", what, mLastError);
        mLastError.clear();
        throw std::runtime_error(msg);
    }
}

}  // namespace twinrender::raymarch
