#include "realtime/per_set_gpu.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>
#include <initializer_list>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/derived_attributes.h"
#include "realtime/field_normal.h"
#include "realtime/gl/context.h"
#include "realtime/gl/conversions.h"
#include "realtime/gl/error.h"
#include "realtime/gl/pipeline.h"
#include "realtime/gl/poison.h"
#include "realtime/gpu_scene.h"
#include "realtime/occlusion_culling.h"
#include "realtime/per_set_layout.h"

namespace twinrender::realtime {

using namespace per_set_layout;

namespace {

// The set's attributes into `out` as the Attributes buffer lays them out (shaders/per_set.glsl):
// each attribute a run of n values from its offset (in units of n floats), those a set lacks
// zero. Copied in parallel chunks: 84 MB at 1M particles.
void stageAttributes(const core::ParticleSet& ps, std::span<std::byte> out) {
    const std::size_t n = ps.size();
    struct Run {
        std::size_t at;           // bytes into `out`
        const std::byte* values;  // nullptr: zeros
        std::size_t bytes;
    };
    auto run = [&](std::size_t offset, const auto& values) {
        const std::size_t bytes = n * sizeof(values[0]);
        return Run{offset * n * sizeof(float),
                   values.size() == n ? reinterpret_cast<const std::byte*>(values.data()) : nullptr,
                   bytes};
    };
    const Run runs[] = {run(0, ps.position), run(3, ps.h),     run(4, ps.volume),
                        run(5, ps.normal),   run(8, ps.body),  run(9, ps.uv),
                        run(11, ps.dudx),    run(14, ps.dvdx), run(17, ps.glow),
                        run(20, ps.material)};
    static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec2) == 8);
    constexpr std::size_t CHUNK = std::size_t(1) << 20;
    std::vector<std::pair<const Run*, std::size_t>> chunks;  // run, first byte
    for (const Run& r : runs)
        for (std::size_t b = 0; b < r.bytes; b += CHUNK) chunks.emplace_back(&r, b);
    tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t k) {
        const auto [r, first] = chunks[k];
        const std::size_t bytes = std::min(CHUNK, r->bytes - first);
        std::byte* to = out.data() + r->at + first;
        if (r->values)
            std::memcpy(to, r->values + first, bytes);
        else
            std::memset(to, 0, bytes);
    });
}

// The Header's first contents (per_set_layout.h), given when it is made: zero counters and
// no work groups in the walk lists' and the sparse list's dispatches (each of their y and z 1).
// INIT, the first stage, sets the rest.
std::vector<std::uint32_t> initialHeader() {
    std::vector<std::uint32_t> words(HEADER_BYTES / 4, 0u);
    for (const std::size_t dispatch : {WALK_DISPATCH, NEXT_WALK_DISPATCH, SPARSE_DISPATCH}) {
        words[dispatch / 4 + 1] = 1u;
        words[dispatch / 4 + 2] = 1u;
    }
    return words;
}

// TWINRENDER_TEST_PER_SET_FAULT=zero_positions (a test hook, read once per process): after
// every upload the particles' positions are cleared to zero on the device, the fault an NVIDIA
// H200 run showed (every particle at one point while h and the volume were right), so that
// the tests can see the self-check, the doctor's stage trace and the CPU fallback find it.
bool zeroPositionsFault() {
    static const bool on = [] {
        const char* value = std::getenv("TWINRENDER_TEST_PER_SET_FAULT");
        return value != nullptr && std::string_view(value) == "zero_positions";
    }();
    return on;
}

bool sameRadiusSettings(const ParticleSettings& a, const ParticleSettings& b) {
    return a.radius == b.radius && a.radiusScale == b.radiusScale &&
           a.surfaceLevel == b.surfaceLevel && a.crossingScale == b.crossingScale &&
           a.interiorLevel == b.interiorLevel && a.dropletAtoms == b.dropletAtoms;
}

// `buffer` kept where it has `bytes` already, else a new one; its contents mean nothing (every
// stage writes what it reads), so in poison mode (gl/poison.h) a kept buffer is poisoned again:
// what the last set left must not stand in for what this one's stages write.
enum class Resized { Kept, New };
Resized resized(gl::Buffer& buffer, std::size_t bytes) {
    if (buffer.size() == std::max<std::size_t>(bytes, 16)) {
        buffer.poison();
        return Resized::Kept;
    }
    buffer = gl::Buffer::storage(bytes);
    return Resized::New;
}
Resized resized(std::optional<gl::Buffer>& buffer, std::size_t bytes) {
    if (buffer) return resized(*buffer, bytes);
    buffer.emplace(gl::Buffer::storage(bytes));
    return Resized::New;
}

}  // namespace

std::vector<std::uint32_t> attributeWords(const core::ParticleSet& particles) {
    std::vector<std::uint32_t> words(ATTRIBUTE_FLOATS * particles.size());
    stageAttributes(particles, std::as_writable_bytes(std::span<std::uint32_t>(words)));
    return words;
}

std::size_t perSetTexels(std::size_t particles) {
    // The cells' offsets, one per cell and one more; the entries take 2 per particle.
    return std::max(maxCells(particles) + 1, 2 * particles);
}

// Whether GL timer queries see compute dispatches on this device: a query around a scan of a
// million values (4 ms on llvmpipe; on a GPU at least the 3 us its 8 MB of memory traffic take)
// reads at least 2 us and no more than the wall clock to a glFinish after it. llvmpipe reads
// 1 ns around compute (and may answer a context's first query with a timestamp). Probed once
// per program cache (a device's programs: ProgramCache::timerQueriesSeeCompute).
bool per_set_layout::timerQueriesSeeCompute(ProgramCache& programs) {
    std::optional<bool>& probed = programs.timerQueriesSeeCompute();
    if (probed) return *probed;
    constexpr std::size_t VALUES = std::size_t(1) << 20;
    const gl::Buffer data = gl::Buffer::zeros(VALUES * sizeof(std::uint32_t));
    const gl::Buffer sums = gl::Buffer::zeros(64 * sizeof(std::uint32_t));
    const gl::Buffer header = gl::Buffer::zeros(HEADER_BYTES);
    data.bindStorage(ATTRIBUTES);
    sums.bindStorage(BLOCK_SUMS);
    header.bindStorage(HEADER);
    const gl::Program& p = programs.compute("scan.comp", {"BLOCKS"});
    p.set("uCount", static_cast<unsigned>(VALUES));
    p.set("uOffset", 0u);
    p.set("uCells", 0);
    bool seen = false;
    for (int probe = 0; probe < 2; ++probe) {
        gl::finish();
        const auto start = std::chrono::steady_clock::now();
        const gl::TimerQuery query;
        query.begin();
        p.dispatch(groups(VALUES, BLOCK));
        query.end();
        gl::finish();
        const double wall =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        const double ms = query.milliseconds();
        seen = ms >= 2e-3 && ms <= wall;
    }
    probed = seen;
    return seen;
}

void GpuPerSet::checkOverruns(const char* stage) const {
    gl::checkConversions("per-set stage", stage);
    if (!gl::poisonMode()) return;
    const std::pair<const char*, const gl::Buffer*> buffers[] = {
        {"attributes", &mAttributes},
        {"header", &mHeader},
        {"cells", &mCells},
        {"cell_of", &mCellOf},
        {"sorted", &mSorted},
        {"entries", &mEntries},
        {"radii", &mRadii},
        {"flags", &mFlags},
        {"block_sums", &mBlockSums},
        {"directions", &mDirections},
        {"models", mModelBuffer ? &*mModelBuffer : nullptr},
        {"draw_lists", mDrawLists ? &*mDrawLists : nullptr},
        {"particles", mParticles ? &*mParticles : nullptr},
        {"ellipsoids", mEllipsoids ? &*mEllipsoids : nullptr},
        {"droplets", &mDroplets},
        {"walks", &mWalks},
        {"droplet_work", &mDropletWork},
        {"cull_spheres", &mCullSpheres},
        {"bodies", &mBodies},
        {"near_masks", &mNearMasks},
        {"placeholder", &mPlaceholder},
    };
    for (const auto& [name, buffer] : buffers)
        if (buffer && buffer->overrun())
            throw gl::Error(fmt::format(
                "per-set stage '{}' wrote past the end of the '{}' buffer ({} bytes): a GPU "
                "would have written into other memory",
                stage, name, buffer->size()));
}

void GpuPerSet::timed(const char* stage, const auto& work) {
    if (stageClock() == StageClock::Queries) {
        const gl::TimerQuery& query = mQueries.emplace_back(stage, gl::TimerQuery()).second;
        query.begin();
        work();
        gl::computeBarrier();
        query.end();
        checkOverruns(stage);
        return;
    }
    // Wall clock to the end of the stage's commands: the next stage waits for this one anyway.
    const auto start = std::chrono::steady_clock::now();
    work();
    gl::computeBarrier();
    gl::finish();
    mTimings[stage] +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    checkOverruns(stage);
}

void GpuPerSet::clearWalks() {
    // No work groups, no entries, in either list.
    const std::uint32_t walkDispatch[8] = {0, 1, 1, 0, 0, 1, 1, 0};
    mHeader.write(WALK_DISPATCH, std::span<const std::uint32_t>(walkDispatch));
}

void GpuPerSet::bindStorage() const {
    mAttributes.bindStorage(ATTRIBUTES);
    mHeader.bindStorage(HEADER);
    mCells.bindStorage(CELLS);
    mCellOf.bindStorage(CELL_OF);
    mEntries.bindStorage(ENTRIES);
    mSorted.bindStorage(SORTED);
    mRadii.bindStorage(RADII);
    mWalks.bindStorage(WALKS);
    mFlags.bindStorage(FLAGS);
    // Every block a stage declares is backed by a buffer, a placeholder where the set has
    // none: a driver may fetch from a block a branch does not take.
    auto orPlaceholder = [&](const gl::Buffer& b) -> const gl::Buffer& {
        return b.size() > 0 ? b : mPlaceholder;
    };
    (mModelBuffer ? *mModelBuffer : mPlaceholder).bindStorage(MODELS);
    if (mDrawLists) mDrawLists->bindStorage(DRAW_LISTS);
    mDirections.bindStorage(DIRECTIONS);
    orPlaceholder(mDroplets).bindStorage(DROPLETS);
    orPlaceholder(mCullSpheres).bindStorage(CULL_SPHERES);
    orPlaceholder(mBodies).bindStorage(BODIES);
    orPlaceholder(mNearMasks).bindStorage(NEAR_MASKS);
    (mEllipsoids ? *mEllipsoids : mPlaceholder).bindStorage(ELLIPSOIDS);
    mDropletWork.bindStorage(DROPLET_WORK);
    mEntryTexels.bind(ENTRY_TEXELS);
    mEntryWordTexels.bind(ENTRY_WORD_TEXELS);
    mCellTexels.bind(CELL_TEXELS);
    mCullSphereTexels.bind(CULL_SPHERE_TEXELS);
    mDirectionTexels.bind(DIRECTION_TEXELS);
}

void GpuPerSet::upload(const core::ParticleSet& ps) {
    const std::size_t n = ps.size();
    mCount = n;
    mMaxCells = maxCells(n);
    // A set of as many particles as the last keeps the buffers: each stage writes what it reads
    // (the grid's counters are cleared in buildGrid), and allocating and zeroing them anew cost
    // more than the rest of the upload.
    const bool kept = resized(mAttributes, ATTRIBUTE_FLOATS * n * sizeof(float)) == Resized::Kept;
    // Into the staging buffer here; buildGrid's first command copies it to the device.
    mStagedBytes = ATTRIBUTE_FLOATS * n * sizeof(float);
    stageAttributes(ps, mStaging.map(mStagedBytes));
    const std::vector<std::uint32_t> header = initialHeader();
    mHeader = gl::Buffer::writableOf(std::span<const std::uint32_t>(header));
    resized(mCells, (mMaxCells + 1) * sizeof(std::uint32_t));
    resized(mCellOf, (n + mMaxCells) * sizeof(std::uint32_t));
    resized(mSorted, n * sizeof(std::uint32_t));
    resized(mEntries, n * GRID_ENTRY_BYTES);
    mCellTexels.view(mCells, gl::BufferFormat::R32UI);
    mEntryTexels.view(mEntries, gl::BufferFormat::RGBA32F);
    mEntryWordTexels.view(mEntries, gl::BufferFormat::RGBA32UI);
    resized(mRadii, n * sizeof(float));
    resized(mWalks, 2 * n * sizeof(std::uint32_t));  // the walk list, the next
    resized(mFlags, n * sizeof(std::uint32_t));
    resized(mDropletWork, 4 * n * sizeof(std::uint32_t));  // per_set_stages.glsl's DropletWork
    resized(mBlockSums,
            (groups(std::max(mMaxCells, 2 * n + 2), BLOCK) + 1) * sizeof(std::uint32_t));
    if (mPlaceholder.size() == 0) mPlaceholder = gl::Buffer::zeros(16);
    if (mDirections.size() == 0) {
        assert(cullingDirections().coarseCount == COARSE_DIRECTIONS);
        std::vector<glm::vec4> directions;
        for (const glm::dvec3& d : cullingDirections().directions)
            directions.emplace_back(glm::vec3(d), 0.0f);
        mDirections = gl::Buffer::of(std::span<const glm::vec4>(directions));
        mDirectionTexels.view(mDirections, gl::BufferFormat::RGBA32F);
    }
    if (!kept) {
        mCullSpheres = gl::Buffer();
        mModelBuffer.reset();
        mEllipsoids.reset();
    } else {
        mCullSpheres.poison();
        if (mModelBuffer) mModelBuffer->poison();
        if (mEllipsoids) mEllipsoids->poison();
    }
    resized(mDrawLists, (n + 1) * sizeof(std::uint32_t));
    resized(mParticles, n * sizeof(GpuParticle));
}

void GpuPerSet::scan(ProgramCache& programs, const gl::Buffer& data, std::size_t offset,
                     std::size_t count, bool cells) {
    data.bindStorage(ATTRIBUTES);
    mBlockSums.bindStorage(BLOCK_SUMS);
    for (const char* stage : {"BLOCKS", "SUMS", "ADD"}) {
        const gl::Program& p = programs.compute("scan.comp", {stage});
        p.set("uCount", static_cast<unsigned>(count));
        p.set("uOffset", static_cast<unsigned>(offset));
        p.set("uCells", cells ? 1 : 0);
        if (std::string_view(stage) == "SUMS")
            p.dispatch(1);
        else if (cells)
            p.dispatchIndirect(mHeader, SCAN_DISPATCH);
        else
            p.dispatch(std::max(groups(count, BLOCK), 1u));
        gl::computeBarrier();
    }
    bindStorage();
}

void GpuPerSet::buildGrid(ProgramCache& programs) {
    auto run = [&](const char* stage, unsigned count) {
        const gl::Program& p = stageProgram(programs, stage);
        p.set("uCount", static_cast<unsigned>(mCount));
        p.dispatch(count);
        gl::computeBarrier();
    };
    mStaging.copyTo(mAttributes, 0, mStagedBytes);  // upload()'s attributes
    if (zeroPositionsFault()) mAttributes.clearRange(0, 3 * mCount * sizeof(float));
    mCells.clear();   // COUNT's counts
    mCellOf.clear();  // SCATTER's fill counts
    bindStorage();
    run("INIT", 1);
    run("H_MIN", groups(mCount, GROUP * REDUCED));
    run("LEVELS", groups(mCount, GROUP * REDUCED));
    run("LAYOUT", 1);
    run("COUNT", groups(mCount));
    scan(programs, mCells, 0, mMaxCells, true);  // the cells LAYOUT made
    run("SCATTER", groups(mCount));
    {
        const gl::Program& p = stageProgram(programs, "SORT");
        p.dispatchIndirect(mHeader, SORT_DISPATCH);
        gl::computeBarrier();
    }
    run("GATHER", groups(mCount));
}

void GpuPerSet::uploadBodies(std::span<const core::BodyInfo> bodies) {
    std::vector<glm::vec4> records;
    records.reserve(2 * bodies.size());
    for (const core::BodyInfo& b : bodies) {
        records.emplace_back(glm::vec3(b.center), 0.0f);
        records.emplace_back(glm::vec3(b.frame[2]), 0.0f);
    }
    mBodies = gl::Buffer::of(std::span<const glm::vec4>(records));
    mBodies.bindStorage(BODIES);
}

void GpuPerSet::deriveNormals(ProgramCache& programs, bool listed) {
    const gl::Program& p = stageProgram(programs, "NORMALS");
    p.set("uCount", static_cast<unsigned>(mCount));
    p.set("uFallbackRatio", static_cast<float>(core::NORMAL_FALLBACK_RATIO));
    p.set("uFromList", listed ? 1 : 0);
    if (listed)
        p.dispatchIndirect(mHeader, WALK_DISPATCH);
    else
        p.dispatch(groups(mCount));
}

bool GpuPerSet::update(ProgramCache& programs, const core::ParticleSet& ps,
                       const PerSetRequest& request,
                       std::span<const core::BodyInfo> deriveNormalsOf) {
    if (!mStageClock)
        mStageClock = timerQueriesSeeCompute(programs) ? StageClock::Queries : StageClock::Finish;
    bool built = false;
    mRequest = request;
    const auto start = std::chrono::steady_clock::now();
    if (!mBuilt || !mKey.matches(ps)) {
        mKey.clear();
        mBuilt = false;
        mRadiusSettings.reset();
        mCulled = false;
        mModelSettings.reset();
        upload(ps);
        mKey.assign(ps);
        mBuilt = true;
        built = true;
    }
    mUploadMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (built && mCount > 0) timed("grid", [&] { buildGrid(programs); });
    if (built) mLevelBoxes.reset();
    const bool derive = !deriveNormalsOf.empty();
    if (built) {
        mNormals = derive ? Normals::None : Normals::Given;
        if (derive && mCount > 0) uploadBodies(deriveNormalsOf);
    }
    if (mCount == 0) return built;
    bindStorage();
    const ParticleSettings& s = request.particles;
    const bool field = s.radius == RadiusModel::Field;
    // The radii depend on droplet_atoms where droplets are drawn (their members' are 0).
    ParticleSettings radiusSettings = s;
    radiusSettings.dropletAtoms = request.droplets ? s.dropletAtoms : 0;
    auto stage = [&](const char* name) -> const gl::Program& {
        const gl::Program& p = stageProgram(programs, name);
        p.set("uCount", static_cast<unsigned>(mCount));
        return p;
    };
    if (!mRadiusSettings || !sameRadiusSettings(*mRadiusSettings, radiusSettings)) {
        auto radiusStage = [&](const char* name) -> const gl::Program& {
            const gl::Program& p = stage(name);
            p.set("uDropletAtoms", radiusSettings.dropletAtoms);
            p.set("uRadiusScale", static_cast<float>(s.radiusScale));
            p.set("uCrossingScale", static_cast<float>(s.crossingScale));
            p.set("uInteriorLevel", static_cast<float>(s.interiorLevel));
            p.set("uLevel", static_cast<float>(s.surfaceLevel));
            p.set("uFixed", field ? 0 : 1);  // a uniform a stage lacks is left alone
            return p;
        };
        timed("radius", [&] {
            mFlags.clear();  // no droplet slots, nothing settled by INTERIOR
            const std::uint32_t zero = 0, noSparse[4] = {0, 1, 1, 0};
            mHeader.write(DROPLET_COUNT * 4, std::span<const std::uint32_t>(&zero, 1));
            mHeader.write(SPARSE_DISPATCH, std::span<const std::uint32_t>(noSparse));
            clearWalks();
            mNearMasksFound = field && request.cull;
            if (field) {
                // The particles deep inside a body; the others listed. With culling, the near
                // shells of the coarse test too.
                if (mNearMasksFound) {
                    resized(mNearMasks, 2 * mCount * sizeof(glm::uvec4));
                    mNearMasks.bindStorage(NEAR_MASKS);
                }
                const gl::Program& p = radiusStage("INTERIOR");
                p.set("uFallbackNormals", mNormals == Normals::Given ? 0 : 1);
                p.set("uNearMasks", mNearMasksFound ? 1 : 0);
                p.dispatch(groups(mCount));
            }
        });
        // The normals the radii need: INTERIOR's list's ("field"), or every particle's.
        if (mNormals != Normals::Given && (field || mNormals != Normals::All)) {
            timed("particle_normals", [&] { deriveNormals(programs, field); });
            mNormals = field ? Normals::Listed : Normals::All;
        }
        timed("radius", [&] {
            // "field": INTERIOR's list (RADIUS_WALK those RADIUS's early exit left);
            // "fixed": every particle.
            if (field)
                radiusStage("RADIUS").dispatchIndirect(mHeader, WALK_DISPATCH);
            else
                radiusStage("RADIUS").dispatch(groups(mCount));
            gl::computeBarrier();
            if (field) radiusStage("RADIUS_WALK").dispatchIndirect(mHeader, NEXT_WALK_DISPATCH);
        });
        if (radiusSettings.dropletAtoms >= 2)
            timed("droplets", [&] { fitDroplets(programs, radiusSettings); });
        mRadiusSettings = radiusSettings;
        mCulled = false;
        mModelSettings.reset();
        built = true;
    }
    if (request.cull && !mCulled) {
        timed("cull", [&] {
            if (mCullSpheres.size() == 0) {
                mCullSpheres = gl::Buffer::storage(mCount * sizeof(glm::vec4));
                mCullSpheres.bindStorage(CULL_SPHERES);
                mCullSphereTexels.view(mCullSpheres, gl::BufferFormat::RGBA32F);
                mCullSphereTexels.bind(CULL_SPHERE_TEXELS);
            }
            clearWalks();
            stage("CULL_SPHERES").dispatch(groups(mCount));
            gl::computeBarrier();
            const CullingDirections& grid = cullingDirections();
            const gl::Program& coarse =
                cullProgram(programs, "CULL", mNearMasksFound ? "NEAR_MASKS" : "");
            coarse.set("uCount", static_cast<unsigned>(mCount));
            coarse.set("uCoarseCosMargin", static_cast<float>(std::cos(grid.coarseCoveringAngle)));
            coarse.set("uCoarseSinMargin", static_cast<float>(std::sin(grid.coarseCoveringAngle)));
            coarse.dispatch(groups(mCount));
            gl::computeBarrier();
            // The spheres the coarse test left (as many work groups as CULL counted) to the
            // probe, then those the probe left (the next list) to the full test.
            for (const char* variant : {"CULL_PROBE", ""}) {
                const gl::Program& full = cullProgram(programs, "CULL_FULL", variant);
                full.set("uCount", static_cast<unsigned>(mCount));
                full.set("uCosMargin", static_cast<float>(std::cos(grid.coveringAngle)));
                full.set("uSinMargin", static_cast<float>(std::sin(grid.coveringAngle)));
                full.set("uRadiusScale", static_cast<float>(s.radiusScale));
                full.dispatchIndirect(mHeader, *variant ? WALK_DISPATCH : NEXT_WALK_DISPATCH);
                gl::computeBarrier();
            }
        });
        mCulled = true;
        built = true;
    }
    // The normals INTERIOR left for later: those of its particles that may be drawn, once the
    // culling has found which (all of them without culling).
    const bool culled = request.cull && mCulled;
    if (mNormals == Normals::Listed || (mNormals == Normals::Drawn && !culled)) {
        timed("particle_normals", [&] {
            clearWalks();
            const gl::Program& p = stage("INTERIOR_DRAWN");
            p.set("uCull", culled ? 1 : 0);
            p.dispatch(groups(mCount));
            gl::computeBarrier();
            deriveNormals(programs, true);
        });
        mNormals = culled ? Normals::Drawn : Normals::All;
        mModelSettings.reset();  // the models read the normals
        built = true;
    }
    const int kind = modelKind(s);
    const bool sameModels = mModelSettings && mModels == kind &&
                            (kind != 2 || mModelSettings->anisotropy == s.anisotropy);
    if (kind != 0 && !sameModels) {
        if (!mModelBuffer) {
            mModelBuffer.emplace(gl::Buffer::storage(3 * mCount * sizeof(glm::vec4)));
            mModelBuffer->bindStorage(MODELS);
        }
        if (kind == 1) {
            timed("field_normals", [&] { stage("FIELD_NORMAL").dispatch(groups(mCount)); });
        } else {
            timed("anisotropy", [&] {
                const gl::Program& p = stage("ANISOTROPY");
                const AnisotropySettings& a = s.anisotropy;
                p.set("uSmoothing", static_cast<float>(a.smoothing));
                p.set("uMaxAxisRatio", static_cast<float>(a.maxAxisRatio));
                p.set("uMinNeighbours", a.minNeighbours);
                p.set("uAnchorSurface", a.anchor == EllipsoidAnchor::Surface ? 1 : 0);
                p.dispatch(groups(mCount));
            });
        }
        mModelSettings = s;
        mModels = kind;
        built = true;
    }
    if (kind == 0) mModels = 0;
    if (built) mMarks.reset();
    return built;
}

void GpuPerSet::fitDroplets(ProgramCache& programs, const ParticleSettings& s) {
    // The ellipsoids of the most droplets a set may hold, 3 vec4 each, then their normal
    // models, 3 vec4 each (shaders/per_set_stages.glsl's dropletModel).
    resized(mDroplets, maxDroplets(mCount) * 6 * sizeof(glm::vec4));
    mDroplets.bindStorage(DROPLETS);
    gl::computeBarrier();  // RADIUS_WALK's list
    for (const char* stage :
         {"DROPLET_EDGES", "DROPLET_CLUSTERS", "DROPLET_LINKS", "DROPLET_FIT"}) {
        const gl::Program& p = stageProgram(programs, stage);
        // A uniform a stage lacks is left alone.
        p.set("uCount", static_cast<unsigned>(mCount));
        p.set("uLevel", static_cast<float>(s.surfaceLevel));
        p.set("uDropletAtoms", s.dropletAtoms);
        p.dispatchIndirect(mHeader, SPARSE_DISPATCH);
        gl::computeBarrier();
    }
}

void GpuPerSet::mark(ProgramCache& programs, const FrameRequest& frame, const Marks& marks) {
    auto stage = [&](const char* name) -> const gl::Program& {
        const gl::Program& p = stageProgram(programs, name);
        p.set("uCount", static_cast<unsigned>(mCount));
        return p;
    };
    timed("pack", [&] {
        bindStorage();
        mParticles->bindStorage(PARTICLES);
        if (mEllipsoids) mEllipsoids->bindStorage(ELLIPSOIDS);
        const std::uint32_t zero = 0;
        mHeader.write(4, std::span<const std::uint32_t>(&zero, 1));  // nearHit
        if (marks.cull) {
            // NEAR over every particle, where NEAR_BOUND finds the camera near enough.
            const gl::Program& bound = stage("NEAR_BOUND");
            bound.set("uCamera", frame.camera);
            bound.set("uNearReach", frame.nearReach);
            bound.set("uRadiusScale", static_cast<float>(mRequest.particles.radiusScale));
            bound.dispatch(1);
            gl::computeBarrier();
            const gl::Program& p = stage("NEAR");
            p.set("uCamera", frame.camera);
            p.set("uNearReach", frame.nearReach);
            p.dispatchIndirect(mHeader, NEAR_DISPATCH);
            gl::computeBarrier();
        }
        {
            clearWalks();
            const gl::Program& p = stage("MARK");
            p.set("uCull", marks.cull ? 1 : 0);
            p.set("uDropletsApart", marks.dropletsApart ? 1 : 0);
            p.dispatch(groups(mCount));
            gl::computeBarrier();
        }
    });
    timed("pack", [&] { scan(programs, *mDrawLists, 0, mCount); });
    mMarks = marks;
}

namespace {
// NEAR_BOUND on the CPU: whether a sphere of a level (radius at most radius_scale times its
// largest h) may reach into the near plane's ball about the camera.
bool mayReachNearPlane(std::span<const GpuPerSet::LevelBox> boxes, const FrameRequest& frame,
                       double radiusScale) {
    for (const GpuPerSet::LevelBox& b : boxes) {
        const glm::dvec3 outside =
            glm::max(glm::max(b.low - frame.camera, frame.camera - b.high), glm::dvec3(0.0));
        // NEAR_BOUND's test with a margin for the GPU's rounding of the same doubles.
        const double distance = glm::length(outside);
        if (distance - radiusScale * b.hMax <= frame.nearReach + 1e-9 * (1.0 + distance))
            return true;
    }
    return false;
}
}  // namespace

void GpuPerSet::afterFrame() {
    if (mCount == 0) return;
    // Marks made where NEAR found no sphere in the near plane's ball hold for every frame whose
    // camera cannot reach one.
    if (mMarks && mMarks->cull && !mMarks->nearFree)
        mMarks->nearFree = mHeader.read<std::uint32_t>(1, 1)[0] == 0;  // the Header's nearHit
    if (mLevelBoxes) return;
    const std::uint32_t used = mHeader.read<std::uint32_t>(USED_LEVELS / 4, 1)[0];
    const std::vector<std::uint32_t> list = mHeader.read<std::uint32_t>(USED_LEVELS / 4 + 1, used);
    // Level: ordered keys of the smallest x, y, z, the count, of the largest x, y, z, the bits
    // of the largest h (per_set.glsl), 16 words each.
    const std::vector<std::uint32_t> levels =
        mHeader.read<std::uint32_t>(LEVELS / 4, 16 * MAX_LEVELS);
    auto fromOrderedKey = [](std::uint32_t k) {
        return std::bit_cast<float>((k & 0x80000000u) ? (k & 0x7FFFFFFFu) : ~k);
    };
    std::vector<LevelBox> boxes;
    for (const std::uint32_t level : list) {
        const std::uint32_t* w = &levels[16 * level];
        boxes.push_back(
            {glm::dvec3(fromOrderedKey(w[0]), fromOrderedKey(w[1]), fromOrderedKey(w[2])),
             glm::dvec3(fromOrderedKey(w[4]), fromOrderedKey(w[5]), fromOrderedKey(w[6])),
             std::bit_cast<float>(w[7])});
    }
    mLevelBoxes = std::move(boxes);
}

void GpuPerSet::pack(ProgramCache& programs, const FrameRequest& frame) {
    if (mCount == 0) return;
    auto stage = [&](const char* name) -> const gl::Program& {
        const gl::Program& p = stageProgram(programs, name);
        p.set("uCount", static_cast<unsigned>(mCount));
        return p;
    };
    if (ellipsoidsDrawn() && !mEllipsoids)
        mEllipsoids.emplace(gl::Buffer::storage(mCount * sizeof(GpuEllipsoid)));
    const bool dropletsApart = this->dropletsApart();
    const bool cull = mRequest.cull && mCulled;
    // The marks of the last frame hold where nothing they depend on changed: the set's answers
    // (update() built nothing), what is drawn apart and, with culling,
    // NEAR's answer, which the camera decides. NEAR_BOUND's test on the CPU, over the levels'
    // boxes read after an earlier frame, tells a camera from which no sphere can reach into the
    // near plane's ball (the usual view: at 1M particles the per-frame marks took 341 ms of
    // a 573 ms frame on an H200).
    const bool nearFree =
        mLevelBoxes && !mayReachNearPlane(*mLevelBoxes, frame, mRequest.particles.radiusScale);
    const Marks marks{cull, dropletsApart, nearFree};
    mMarksReused = mMarks && mMarks->cull == cull && mMarks->dropletsApart == dropletsApart &&
                   (!cull || (mMarks->nearFree && nearFree));
    if (!mMarksReused) mark(programs, frame, marks);
    timed("pack", [&] {
        bindStorage();
        mParticles->bindStorage(PARTICLES);
        if (mEllipsoids) mEllipsoids->bindStorage(ELLIPSOIDS);
        const gl::Program& p = stage("PACK");
        p.set("uCamera", frame.camera);
        p.set("uModels", mModels);
        p.set("uDropletsApart", dropletsApart ? 1 : 0);
        p.dispatchIndirect(mHeader, WALK_DISPATCH);  // the drawn particles MARK listed
        gl::computeBarrier();
        const gl::Program& finish = stage("FINISH");
        finish.set("uDropletsApart", dropletsApart ? 1 : 0);
        finish.dispatch(1);
    });
}

void GpuPerSet::countReplaced(ProgramCache& programs, const gl::Buffer& bodyMask) {
    if (mCount == 0) return;
    timed("pack", [&] {
        bindStorage();
        bodyMask.bindStorage(BODY_MASK);
        const gl::Program& p = stageProgram(programs, "REPLACED");
        p.set("uCount", static_cast<unsigned>(mCount));
        p.dispatchIndirect(mHeader, WALK_DISPATCH);  // the drawn particles MARK listed
    });
}

void GpuPerSet::gatherGradient(ProgramCache& programs, const gl::Texture& surface,
                               gl::Texture& gradient, const glm::dvec3& camera,
                               const gl::Buffer* bodyMask, bool testKernelBodies) {
    bindStorage();
    surface.bind(0);
    gradient.bindImageForWriting(0);
    if (bodyMask) bodyMask->bindStorage(BODY_MASK);
    std::vector<std::string> defines;
    if (bodyMask) defines.emplace_back("BODY_MASK");
    if (bodyMask && testKernelBodies) defines.emplace_back("KERNEL_BODIES");
    const gl::Program& p = programs.compute("gradient_gather.comp", defines);
    p.set("uCamera", camera);
    p.dispatch(groups(gradient.width(), 8), groups(gradient.height(), 8));
    gl::computeBarrier();  // the resolve fetches the gradient
}

std::map<std::string, double> GpuPerSet::takeTimings() {
    for (const auto& [stage, query] : mQueries) mTimings[stage] += query.milliseconds();
    mQueries.clear();
    return std::exchange(mTimings, {});
}

}  // namespace twinrender::realtime
