#include "app/reference_cache.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <optional>

#include "app/build_identity.h"
#include "app/content_hash.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/image_io.h"

namespace twinrender::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Bump when the cached reference's format or what goes into its key changes.
constexpr const char* CACHE_KEY_VERSION = "twinrender-reference-v1";

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
        if (!o.starts_with("realtime.")) {
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

namespace {

// The cached render in `dir`, or nothing when the entry is not a whole, readable render of
// this scene's size (a folder left by an older version, a file damaged on disk): the caller
// renders it anew.
std::optional<core::Frame> readEntry(const LoadedScene& s, const fs::path& dir, std::string& why) {
    const fs::path exr = dir / "raymarch.exr", meta = dir / "raymarch.json";
    if (!fs::is_regular_file(exr) || !fs::is_regular_file(meta) ||
        !fs::is_regular_file(dir / "key.json")) {
        why = "incomplete";
        return std::nullopt;
    }
    core::Frame r;
    try {
        r = core::readFrame(dir, "raymarch");
    } catch (const core::InputError& e) {
        why = e.what();
        return std::nullopt;
    }
    // EXR keeps channels in its own order: compare them as sets.
    auto names = r.image.channelNames(), expected = core::aov::channelNames();
    std::sort(names.begin(), names.end());
    std::sort(expected.begin(), expected.end());
    if (r.image.width() != s.scene.camera.width || r.image.height() != s.scene.camera.height ||
        names != expected || r.part) {
        why = fmt::format("{}: {}x{} with other channels than a reference render of {}x{}{}",
                          exr.string(), r.image.width(), r.image.height(), s.scene.camera.width,
                          s.scene.camera.height, r.part ? ", or one part of it" : "");
        return std::nullopt;
    }
    r.display = core::tonemappedBeauty(r.image, static_cast<float>(s.scene.camera.exposure));
    return r;
}

// A name in the cache folder that no other process and no other call of this one uses.
fs::path uniqueName(const fs::path& dir, const std::string& stem) {
    static std::atomic<unsigned> counter{0};
    return dir / fmt::format(".{}.tmp{}-{}", stem, getpid(), counter++);
}

// Puts the entry written in `staged` at `dir` by one rename of the folder: a process that
// shares the cache sees no entry or a whole one. When another process has put its entry
// there first (rename fails: the folder exists and is not empty), that one stays (the same
// render: the key says everything it depends on) and `staged` goes. A `stale` entry (one
// readEntry refused) is moved aside first.
void publish(const fs::path& staged, const fs::path& dir, bool stale) {
    std::error_code ec;
    if (stale) {
        const fs::path aside = uniqueName(dir.parent_path(), dir.filename().string() + ".stale");
        fs::rename(dir, aside, ec);
        fs::remove_all(aside, ec);
    }
    fs::rename(staged, dir, ec);
    if (ec) fs::remove_all(staged, ec);
}

}  // namespace

const core::Frame& ReferenceCache::get(const LoadedScene& s, const std::string& key,
                                       const json& what) {
    if (auto it = mLoaded.find(key); it != mLoaded.end()) return it->second;
    const fs::path dir = mDir / key;
    std::string why;
    std::optional<core::Frame> cached;
    const bool exists = fs::exists(dir);
    if (exists) cached = readEntry(s, dir, why);
    core::Frame r;
    if (cached) {
        r = std::move(*cached);
        std::printf("reference %s: cache hit %s\n", key.c_str(), dir.c_str());
    } else {
        if (exists)
            std::printf("reference %s: cached render unusable (%s), rendering anew\n", key.c_str(),
                        why.c_str());
        r = render("raymarch", mDevices, s);
        // Written whole under a name of this process's own, then put in place (publish).
        const fs::path staged = uniqueName(mDir, key);
        try {
            writeRender(s, r, staged);
            core::writeTextFile(staged / "key.json", what.dump(2) + "\n");
        } catch (...) {
            std::error_code ec;
            fs::remove_all(staged, ec);
            throw;
        }
        publish(staged, dir, exists);
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
