#include "realtime/frame_graph.h"

#include <gtest/gtest.h>

#include <array>

#include "realtime/gl/error.h"

namespace tr = twinrender::realtime;
using tr::Resource;

TEST(FrameGraph, APassTouchesOnlyWhatItDeclares) {
    // No texture is made: the checks come before any GL object is touched.
    tr::FrameResources all;
    constexpr std::array reads{Resource::NormalUv, Resource::Occlusion};
    constexpr std::array writes{Resource::Beauty};
    tr::PassResources pass("shade", all, reads, writes);
    // Declared and not yet written: find says none, read throws naming the resource.
    EXPECT_EQ(pass.find(Resource::Occlusion), nullptr);
    try {
        pass.read(Resource::NormalUv);
        FAIL() << "read an unwritten resource";
    } catch (const tr::gl::Error& e) {
        EXPECT_NE(std::string(e.what()).find("normal + uv"), std::string::npos) << e.what();
    }
    // Not declared: a read or a write names the pass and the resource.
    try {
        pass.find(Resource::ShadowMap);
        FAIL() << "read an undeclared resource";
    } catch (const tr::gl::Error& e) {
        EXPECT_NE(std::string(e.what()).find("pass 'shade' reads the shadow map"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(pass.gbuffer(), tr::gl::Error);
    EXPECT_THROW(pass.write(Resource::Display, tr::gl::Texture()), tr::gl::Error);
    EXPECT_EQ(all.find(Resource::Display), nullptr);  // the refused write left nothing
    // A declared write is the current version for the passes after it.
    pass.write(Resource::Beauty, tr::gl::Texture());
    EXPECT_NE(all.find(Resource::Beauty), nullptr);
}
