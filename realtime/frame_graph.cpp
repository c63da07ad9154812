#include "realtime/frame_graph.h"

#include <fmt/format.h>

#include <algorithm>

#include "realtime/gl/error.h"

namespace twinrender::realtime {

std::string_view toString(Resource resource) {
    switch (resource) {
        case Resource::ShadowMap:
            return "shadow map";
        case Resource::GBuffer:
            return "G-buffer";
        case Resource::NormalUv:
            return "normal + uv";
        case Resource::Emission:
            return "emission";
        case Resource::Surface:
            return "surface";
        case Resource::Occlusion:
            return "occlusion";
        case Resource::Irradiance:
            return "irradiance";
        case Resource::Beauty:
            return "beauty";
        case Resource::Inscatter:
            return "inscatter";
        case Resource::Display:
            return "display";
    }
    return "?";
}

namespace {
std::size_t slot(Resource resource) {
    return static_cast<std::size_t>(resource);
}
}  // namespace

const gl::Texture* FrameResources::find(Resource resource) const {
    return mCurrent[slot(resource)];
}

const gl::Texture& FrameResources::read(Resource resource) const {
    const gl::Texture* t = find(resource);
    if (!t)
        throw gl::Error(
            fmt::format("the frame's {} is read before a pass wrote it", toString(resource)));
    return *t;
}

const GBuffer& FrameResources::gbuffer() const {
    if (!mGBuffer) throw gl::Error("the frame's G-buffer is read before the G-buffer pass ran");
    return *mGBuffer;
}

void FrameResources::write(Resource resource, std::shared_ptr<const void> owner,
                           const gl::Texture& texture) {
    mOwners.push_back(std::move(owner));
    mCurrent[slot(resource)] = &texture;
}

void FrameResources::write(Resource resource, gl::Texture&& texture) {
    auto owner = std::make_shared<const gl::Texture>(std::move(texture));
    const gl::Texture& t = *owner;
    write(resource, std::move(owner), t);
}

void FrameResources::writeGBuffer(GBuffer&& gbuffer) {
    mGBuffer = std::make_shared<const GBuffer>(std::move(gbuffer));
    mCurrent[slot(Resource::GBuffer)] = &mGBuffer->depth;
    mCurrent[slot(Resource::NormalUv)] = &mGBuffer->normalUv;
    mCurrent[slot(Resource::Emission)] = &mGBuffer->emission;
    mCurrent[slot(Resource::Surface)] = &mGBuffer->surface;
}

PassResources::PassResources(std::string_view pass, FrameResources& all,
                             std::span<const Resource> reads, std::span<const Resource> writes)
    : mPass(pass), mAll(all), mReads(reads), mWrites(writes) {}

void PassResources::check(Resource resource, std::span<const Resource> declared,
                          const char* what) const {
    if (std::find(declared.begin(), declared.end(), resource) == declared.end())
        throw gl::Error(fmt::format("pass '{}' {} the {}, which it does not declare", mPass, what,
                                    toString(resource)));
}

const gl::Texture& PassResources::read(Resource resource) const {
    check(resource, mReads, "reads");
    return mAll.read(resource);
}

const gl::Texture* PassResources::find(Resource resource) const {
    check(resource, mReads, "reads");
    return mAll.find(resource);
}

const GBuffer& PassResources::gbuffer() const {
    check(Resource::GBuffer, mReads, "reads");
    return mAll.gbuffer();
}

void PassResources::write(Resource resource, std::shared_ptr<const void> owner,
                          const gl::Texture& texture) {
    check(resource, mWrites, "writes");
    mAll.write(resource, std::move(owner), texture);
}

void PassResources::write(Resource resource, gl::Texture&& texture) {
    check(resource, mWrites, "writes");
    mAll.write(resource, std::move(texture));
}

void PassResources::writeGBuffer(GBuffer&& gbuffer) {
    for (Resource r :
         {Resource::GBuffer, Resource::NormalUv, Resource::Emission, Resource::Surface})
        check(r, mWrites, "writes");
    mAll.writeGBuffer(std::move(gbuffer));
}

}  // namespace twinrender::realtime
