// Reference renders cached on disk, shared by `sweep` and `study`: a render is stored under a
// hash of everything that affects it (the scene file and the files it names, the overrides
// other than realtime.*, the parsed raymarch settings, and the build identity of the
// raymarcher, app/build_identity.h), with key.json beside it saying what went in.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "app/render_job.h"

namespace twinrender::app {

// The cache key (16 hex digits) of the reference render of a scene loaded with `overrides`,
// and a readable account of what went into it.
std::pair<std::string, nlohmann::json> referenceKey(const LoadedScene& scene,
                                                    const std::vector<std::string>& overrides);

// A reference render from the cache folder, or rendered and stored there. Prints one line per
// render or hit ("reference KEY: cache hit DIR" / "... rendered in N ms, cached in DIR").
class ReferenceCache {
  public:
    ReferenceCache(std::filesystem::path dir, Devices& devices)
        : mDir(std::move(dir)), mDevices(devices) {}

    const core::Frame& get(const LoadedScene& scene, const std::string& key,
                           const nlohmann::json& what);
    // Lets go of the render of `key` held in memory (a sequence's past frame); a later get()
    // reads it from the folder again.
    void forget(const std::string& key);

  private:
    std::filesystem::path mDir;
    Devices& mDevices;
    std::map<std::string, core::Frame> mLoaded;
};

}  // namespace twinrender::app
