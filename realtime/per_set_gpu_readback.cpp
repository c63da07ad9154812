// GpuPerSet's read-backs: the counters after a frame, and the per-particle answers and stage
// records that tests and the doctor's self-check compare.
#include <bit>
#include <glm/vec4.hpp>
#include <utility>
#include <vector>

#include "realtime/per_set_gpu.h"
#include "realtime/per_set_layout.h"

namespace twinrender::realtime {

using namespace per_set_layout;

std::uint32_t GpuPerSet::drawnCount() const {
    if (mCount == 0) return 0;
    const std::uint32_t particles = mHeader.read<std::uint32_t>(particleDrawOffset() / 4, 1)[0] / 6;
    return particles + (dropletsApart() ? dropletCount() : 0);
}

std::uint32_t GpuPerSet::dropletCount() const {
    if (mCount == 0) return 0;
    return mHeader.read<std::uint32_t>(DROPLET_COUNT, 1)[0];
}

std::size_t GpuPerSet::dropletDrawOffset() {
    return DROPLET_DRAW;
}

std::vector<float> GpuPerSet::radii() const {
    return mRadii.read<float>(0, mCount);
}

std::vector<glm::vec3> GpuPerSet::normals() const {
    const std::vector<float> xyz = mAttributes.read<float>(5 * mCount, 3 * mCount);
    std::vector<glm::vec3> out(mCount);
    for (std::size_t i = 0; i < mCount; ++i)
        out[i] = glm::vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    return out;
}

std::vector<std::uint32_t> GpuPerSet::visibleParticles() const {
    const std::vector<std::uint32_t> flags = mFlags.read<std::uint32_t>(0, mCount);
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < flags.size(); ++i)
        if (!(flags[i] & 2u)) out.push_back(static_cast<std::uint32_t>(i));
    return out;
}

std::vector<std::pair<std::uint32_t, Ellipsoid>> GpuPerSet::droplets() const {
    const std::uint32_t count = dropletCount();
    if (count == 0) return {};
    const std::vector<std::uint32_t> flags = mFlags.read<std::uint32_t>(0, mCount);
    const std::vector<glm::vec4> records = mDroplets.read<glm::vec4>(0, 3 * count);
    std::vector<std::pair<std::uint32_t, Ellipsoid>> out;
    for (std::size_t i = 0; i < flags.size(); ++i) {
        const std::uint32_t slot = flags[i] >> DROPLET_SHIFT;
        if (slot == 0) continue;
        Ellipsoid e;
        for (int a = 0; a < 3; ++a) {
            const glm::vec4& r = records[3 * (slot - 1) + a];
            e.axes[a] = glm::vec3(r);
            e.shift[a] = r.w;
        }
        out.emplace_back(static_cast<std::uint32_t>(i), e);
    }
    return out;
}

GpuPerSet::Grid GpuPerSet::grid() const {
    Grid g;
    if (mCount == 0) return g;
    g.totalCells = mHeader.read<std::uint32_t>(2, 1)[0];  // the Header's totalCells
    g.sorted = mSorted.read<std::uint32_t>(0, mCount);
    g.cellStart = mCells.read<std::uint32_t>(0, std::min<std::size_t>(g.totalCells, mMaxCells) + 1);
    const std::vector<glm::uvec4> words = mEntries.read<glm::uvec4>(0, 2 * mCount);
    for (std::size_t k = 0; k < mCount; ++k) {
        const glm::uvec4& p = words[2 * k];
        g.entryPosition.emplace_back(std::bit_cast<float>(p.x), std::bit_cast<float>(p.y),
                                     std::bit_cast<float>(p.z));
        g.entryIndex.push_back(words[2 * k + 1].z);
    }
    return g;
}

std::vector<std::uint32_t> GpuPerSet::flags() const {
    return mFlags.read<std::uint32_t>(0, mCount);
}

std::vector<std::uint32_t> GpuPerSet::drawnPrefix() const {
    if (!mDrawLists || mCount == 0) return {};
    return mDrawLists->read<std::uint32_t>(0, mCount + 1);
}

std::vector<glm::vec4> GpuPerSet::models() const {
    if (!mModelBuffer) return {};
    return mModelBuffer->read<glm::vec4>(0, 3 * mCount);
}

std::vector<std::uint32_t> GpuPerSet::attributes() const {
    return mAttributes.read<std::uint32_t>(0, ATTRIBUTE_FLOATS * mCount);
}

GpuPerSet::Levels GpuPerSet::levels() const {
    Levels out;
    if (mCount == 0) return out;
    const std::vector<std::uint32_t> head = mHeader.read<std::uint32_t>(0, 4);
    out.hMin = std::bit_cast<float>(head[0]);  // the Header's hMinBits
    out.totalCells = head[2];
    auto fromOrderedKey = [](std::uint32_t k) {
        return std::bit_cast<float>((k & 0x80000000u) ? (k & 0x7FFFFFFFu) : ~k);
    };
    // Level (shaders/per_set.glsl): 8 uints, originCell, dims; 16 words.
    const std::vector<std::uint32_t> w = mHeader.read<std::uint32_t>(LEVELS / 4, 16 * MAX_LEVELS);
    for (int L = 0; L < MAX_LEVELS; ++L) {
        const std::uint32_t* l = &w[16 * static_cast<std::size_t>(L)];
        out.levels.push_back(
            {.low = {fromOrderedKey(l[0]), fromOrderedKey(l[1]), fromOrderedKey(l[2])},
             .high = {fromOrderedKey(l[4]), fromOrderedKey(l[5]), fromOrderedKey(l[6])},
             .count = l[3],
             .hMax = std::bit_cast<float>(l[7]),
             .originCell = {std::bit_cast<float>(l[8]), std::bit_cast<float>(l[9]),
                            std::bit_cast<float>(l[10]), std::bit_cast<float>(l[11])},
             .dims = {static_cast<int>(l[12]), static_cast<int>(l[13]), static_cast<int>(l[14]),
                      static_cast<int>(l[15])}});
    }
    return out;
}

}  // namespace twinrender::realtime
