// The textures a frame's passes hand each other (passes.h), by name. Each pass declares what
// it reads and what it writes, as the passes of Filament's frame graph do (without its culling
// and memory aliasing): it may read only what it declared, and what an earlier pass wrote; a
// write makes a new version that the passes after it read. The surface passes write the
// normal + uv over the G-buffer's, and the shade pass reads whichever came last without asking
// which passes ran.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "realtime/passes.h"

namespace twinrender::realtime {

enum class Resource {
    ShadowMap,   // the light's depth map, or its filtered moments
    GBuffer,     // the G-buffer pass's targets as drawn (struct GBuffer), its depth among them
    NormalUv,    // octahedral normal + uv: the G-buffer's, then each surface pass's
    Emission,    // the emission buffer: the G-buffer's, then SSSS's or the user shader's
    Surface,     // eye depth, body, radius, material: the G-buffer's, or a depth filter's
    Occlusion,   // the ambient occlusion's open fraction
    Irradiance,  // the emissive light's irradiance
    Beauty,      // linear beauty and the sun's visibility
    Inscatter,   // the atmosphere's in-scatter
    Display,     // bloom and tonemap
};
inline constexpr std::size_t RESOURCE_COUNT = 10;
std::string_view toString(Resource resource);

// Every resource's current version, and what keeps each alive until the frame ends.
class FrameResources {
  public:
    // Null when no pass wrote it.
    const gl::Texture* find(Resource resource) const;
    // Throws gl::Error naming the resource when no pass wrote it.
    const gl::Texture& read(Resource resource) const;
    const GBuffer& gbuffer() const;

    // Makes `texture`, which `owner` holds, the resource's current version.
    void write(Resource resource, std::shared_ptr<const void> owner, const gl::Texture& texture);
    void write(Resource resource, gl::Texture&& texture);
    // The G-buffer, and its normal + uv, emission and surface as those resources' first versions.
    void writeGBuffer(GBuffer&& gbuffer);

  private:
    std::array<const gl::Texture*, RESOURCE_COUNT> mCurrent{};
    std::shared_ptr<const GBuffer> mGBuffer;
    std::vector<std::shared_ptr<const void>> mOwners;
};

// What one pass may touch of the frame's resources: its declared reads and writes. A read or
// write it did not declare throws gl::Error naming the pass and the resource.
class PassResources {
  public:
    PassResources(std::string_view pass, FrameResources& all, std::span<const Resource> reads,
                  std::span<const Resource> writes);

    // A declared read: the current version (throws when no pass wrote it), or null (find).
    const gl::Texture& read(Resource resource) const;
    const gl::Texture* find(Resource resource) const;
    const GBuffer& gbuffer() const;  // declared as a read of Resource::GBuffer

    void write(Resource resource, std::shared_ptr<const void> owner, const gl::Texture& texture);
    void write(Resource resource, gl::Texture&& texture);
    void writeGBuffer(GBuffer&& gbuffer);  // declared as a write of GBuffer and its three

  private:
    void check(Resource resource, std::span<const Resource> declared, const char* what) const;
    std::string_view mPass;
    FrameResources& mAll;
    std::span<const Resource> mReads, mWrites;
};

}  // namespace twinrender::realtime
