#include "realtime/particle_set_key.h"

#include <gtest/gtest.h>

#include <span>
#include <stdexcept>
#include <vector>

namespace twinrender::realtime {
namespace {

core::ParticleSet twoParticles() {
    core::ParticleSet ps;
    ps.position = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
    ps.h = {0.5f, 0.5f};
    ps.volume = {0.1f, 0.1f};
    return ps;
}

// An answer that counts how often it was computed, keyed by the set, a level and radii.
struct Counted {
    int computed = 0;
    SetCache<int, double, std::span<const float>> cache;
    int get(const core::ParticleSet& ps, double level, const std::vector<float>& radii) {
        return cache.get(
            ps, [&] { return ++computed; }, level, std::span<const float>(radii));
    }
};

TEST(SetCache, ComputesOnceForTheSameInputsAndAgainWhenAnyChanges) {
    Counted c;
    core::ParticleSet ps = twoParticles();
    std::vector<float> radii = {0.4f, 0.4f};
    EXPECT_EQ(c.get(ps, 0.5, radii), 1);
    EXPECT_FALSE(c.cache.reused());
    EXPECT_EQ(c.get(ps, 0.5, radii), 1);
    EXPECT_TRUE(c.cache.reused());
    EXPECT_EQ(c.get(ps, 0.6, radii), 2);  // another level
    EXPECT_FALSE(c.cache.reused());
    radii[1] = 0.41f;
    EXPECT_EQ(c.get(ps, 0.6, radii), 3);  // another radius
    ps.position[0].z = 1e-7f;
    EXPECT_EQ(c.get(ps, 0.6, radii), 4);  // a moved particle
    ps.h[1] = 0.51f;
    EXPECT_EQ(c.get(ps, 0.6, radii), 5);  // another h
    EXPECT_EQ(c.get(ps, 0.6, radii), 5);
    EXPECT_TRUE(c.cache.reused());
    radii.push_back(0.4f);
    EXPECT_EQ(c.get(ps, 0.6, radii), 6);  // as many radii as before, and one more
}

TEST(SetCache, AnAnswerInterruptedByAnExceptionIsNotKept) {
    SetCache<int> cache;
    const core::ParticleSet ps = twoParticles();
    EXPECT_EQ(cache.get(ps, [] { return 7; }), 7);
    const core::ParticleSet other = [] {
        core::ParticleSet moved = twoParticles();
        moved.position[1].x = 2.0f;
        return moved;
    }();
    EXPECT_THROW(cache.get(other, []() -> int { throw std::runtime_error("stopped"); }),
                 std::runtime_error);
    // Neither the set that threw nor the one before it is taken as kept.
    EXPECT_EQ(cache.get(ps, [] { return 8; }), 8);
    EXPECT_FALSE(cache.reused());
}

}  // namespace
}  // namespace twinrender::realtime
