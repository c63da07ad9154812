// What the real-time renderer's per-particle-set answers (occlusion culling, impostor radii,
// field normal models, ellipsoids, droplets, surface kernels, derived normals) depend on, kept
// to tell a new particle set from the last one, and SetCache: such an answer kept while its
// inputs are unchanged.
#pragma once

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "core/derived_attributes.h"
#include "core/particles.h"

namespace twinrender::realtime {

// A copy of the attributes that shape the surface (positions, h, volumes, normals, bodies).
// Compared exactly: about 1 ms per 100k particles, against the 5-300 ms of the answers kept.
class ParticleSetKey {
  public:
    // Whether `particles` has exactly the attributes last assigned (false before that).
    bool matches(const core::ParticleSet& particles) const {
        return mValid && particles.position == mPosition && particles.h == mH &&
               particles.volume == mVolume && particles.normal == mNormal &&
               particles.body == mBody;
    }
    // The five copies side by side (36 MB at 1M particles, in every frame of a sequence).
    void assign(const core::ParticleSet& particles) {
        tbb::parallel_invoke([&] { mPosition = particles.position; }, [&] { mH = particles.h; },
                             [&] { mVolume = particles.volume; },
                             [&] { mNormal = particles.normal; }, [&] { mBody = particles.body; });
        mValid = true;
    }
    // Forgets the set, so that an answer interrupted by an exception is not taken as kept.
    void clear() { mValid = false; }

  private:
    bool mValid = false;
    std::vector<glm::vec3> mPosition, mNormal;
    std::vector<float> mH, mVolume;
    std::vector<std::uint32_t> mBody;
};

// Whether a span holds exactly the values kept.
template <typename T>
bool sameValues(std::span<const T> values, const std::vector<T>& kept) {
    return std::equal(values.begin(), values.end(), kept.begin(), kept.end());
}

namespace detail {
// One input of a SetCache answer besides the set: a value compared with ==, kept as it is.
template <typename T>
struct KeptInput {
    T value{};
    bool same(const T& v) const { return value == v; }
    void keep(const T& v) { value = v; }
};
// A span (radii, indices) compared element by element, kept as a vector.
template <typename T>
struct KeptInput<std::span<const T>> {
    std::vector<T> value;
    bool same(std::span<const T> v) const { return sameValues(v, value); }
    void keep(std::span<const T> v) { value.assign(v.begin(), v.end()); }
};
}  // namespace detail

// The last answer of a per-particle-set computation, kept while its inputs are unchanged: the
// set (ParticleSetKey, compared exactly) and `Inputs` (settings and the like with ==, spans
// element by element). The CPU path's caches are each one of these; the frames of an unchanged
// set reuse their answers.
template <typename Answer, typename... Inputs>
class SetCache {
  public:
    // The answer for `particles` and `inputs`: compute()'s, unless the last call's inputs were
    // the same. An exception from compute() leaves nothing kept.
    template <typename Compute>
    const Answer& get(const core::ParticleSet& particles, Compute&& compute,
                      const Inputs&... inputs) {
        mReused =
            mKey.matches(particles) &&
            std::apply([&](const auto&... kept) { return (kept.same(inputs) && ...); }, mInputs);
        if (!mReused) {
            mKey.clear();
            mAnswer = std::forward<Compute>(compute)();
            std::apply([&](auto&... kept) { (kept.keep(inputs), ...); }, mInputs);
            mKey.assign(particles);
        }
        return mAnswer;
    }
    // Whether the last get() returned the kept answer.
    bool reused() const { return mReused; }

  private:
    bool mReused = false;
    ParticleSetKey mKey;
    std::tuple<detail::KeptInput<Inputs>...> mInputs;
    Answer mAnswer{};
};

// The CPU's per-set work (per_set = "cpu") and the traced occlusion's spheres (ao_traced.h): a
// set that came without normals (core::buildParticles leaves them to the real-time renderer),
// copied with core::deriveNormals' normals and kept for the set.
class DerivedNormalsCache {
  public:
    const core::ParticleSet& particles(const core::SceneParticles& in) {
        mGiven = in.hasNormals;
        if (mGiven) return in.particles;
        return mCache.get(in.particles, [&] {
            core::ParticleSet out = in.particles;
            core::deriveNormals(out, in.bodies);
            return out;
        });
    }
    bool reused() const { return mGiven || mCache.reused(); }

  private:
    bool mGiven = false;
    SetCache<core::ParticleSet> mCache;
};

}  // namespace twinrender::realtime
