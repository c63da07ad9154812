#include "app/reference_cache.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "app/build_identity.h"
#include "core/error.h"
#include "core/image_io.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Bump when the cached reference's format or what goes into its key changes.
constexpr const char* CACHE_KEY_VERSION = "twinrender-reference-v1";

bool startsWith(const std::string& s, const char* prefix) {
    return s.rfind(prefix, 0) == 0;
}

// FNV-1a, 64 bits: a cache key, not a security boundary.
class Hash {
  public:
    void add(std::string_view bytes) {
        for (unsigned char c : bytes) {
            mState ^= c;
            mState *= 0x100000001b3ULL;
        }
        // A separator, so that ("ab", "c") and ("a", "bc") differ.
        mState ^= 0xff;
        mState *= 0x100000001b3ULL;
    }
    void addFile(const fs::path& file) {
        std::ifstream in(file, std::ios::binary);
        if (!in) throw core::InputError(fmt::format("{}: cannot be read", file.string()));
        add(file.string());
        add(std::string(std::istreambuf_iterator<char>(in), {}));
    }
    std::string hex() const { return fmt::format("{:016x}", mState); }

  private:
    std::uint64_t mState = 0xcbf29ce484222325ULL;
};

}  // namespace

// The cache key of a reference render, and a readable account of what went into it:
// everything the raymarcher reads (the scene file and the files it names, the overrides
// other than realtime.*, the parsed raymarch settings) and the code that renders it (the
// build identity), nothing only the real-time renderer reads.
std::pair<std::string, json> referenceKey(const LoadedScene& s,
                                          const std::vector<std::string>& overrides) {
    Hash h;
    json what;
    h.add(CACHE_KEY_VERSION);
    h.add(referenceBuildIdentity());
    what["build"] = referenceBuildIdentity();
    h.addFile(s.scene.file);
    what["scene_file"] = s.scene.file.string();
    std::vector<std::string> used;
    for (const auto& o : overrides)
        if (!startsWith(o, "realtime.")) {
            h.add(o);
            used.push_back(o);
        }
    what["overrides"] = used;
    json files = json::array();
    for (const auto& b : s.scene.bodies)
        if (!b.path.empty()) {
            h.addFile(b.path);
            files.push_back(b.path.string());
        }
    for (const auto& m : s.scene.materials)
        for (const core::TextureSource* t : {&m.diffuse, &m.specular, &m.emission, &m.cityLights})
            if (t->kind == core::TextureSource::Kind::File) {
                h.addFile(t->path);
                files.push_back(t->path.string());
            }
    what["files"] = files;
    // A sequence's frame: where its moving bodies and its camera are (its file bodies' files
    // are hashed above).
    if (s.scene.sequence) {
        h.add(fmt::format("frame={}", s.scene.frame));
        what["frame"] = s.scene.frame;
    }
    const json settings = raymarch::toJson(s.raymarch);
    h.add(settings.dump());
    what["raymarch"] = settings;
    what["version"] = CACHE_KEY_VERSION;
    return {h.hex(), what};
}

const core::Frame& ReferenceCache::get(const LoadedScene& s, const std::string& key,
                                       const json& what) {
    if (auto it = mLoaded.find(key); it != mLoaded.end()) return it->second;
    const fs::path dir = mDir / key;
    core::Frame r;
    if (fs::is_regular_file(dir / "raymarch.exr") && fs::is_regular_file(dir / "raymarch.json")) {
        r.image = core::readImage(dir / "raymarch.exr");
        std::ifstream in(dir / "raymarch.json");
        const json j = json::parse(in, nullptr, false);
        if (j.is_discarded())
            throw core::InputError(
                fmt::format("{}: not JSON; delete the folder", (dir / "raymarch.json").string()));
        r.renderer = "raymarch";
        r.device = j.value("device", "");
        r.settings = j.value("settings", json());
        const json timings = j.value("timings_ms", json::object());
        const json counters = j.value("counters", json::object());
        for (const auto& [k, v] : timings.items())
            if (v.is_number()) r.timingsMs[k] = v.get<double>();
        for (const auto& [k, v] : counters.items())
            if (v.is_number()) r.counters[k] = v.get<double>();
        r.particleCount = j.value("particle_count", std::size_t{0});
        r.display = core::tonemappedBeauty(r.image, static_cast<float>(s.scene.camera.exposure));
        std::printf("reference %s: cache hit %s\n", key.c_str(), dir.c_str());
    } else {
        r = render("raymarch", mDevices, s);
        writeRender(s, r, dir);
        core::writeTextFile(dir / "key.json", what.dump(2) + "\n");
        std::printf("reference %s: rendered in %.1f ms, cached in %s\n", key.c_str(),
                    r.timingsMs.at("total"), dir.c_str());
    }
    std::fflush(stdout);
    return mLoaded.emplace(key, std::move(r)).first->second;
}

void ReferenceCache::forget(const std::string& key) {
    mLoaded.erase(key);
}

}  // namespace twinrender::app
